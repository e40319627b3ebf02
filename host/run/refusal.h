// refusal.h: what the pipeline refuses of a request (a stack that cannot be traced so, options that do not go
// together), before any work: thrown as a RequestRefused, which the command line says as it says a refused option
// (the message, where the command's usage is, exit 2).
#pragma once
#include <stdexcept>
#include <string>

namespace gonio {

struct RequestRefused : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};
[[noreturn]] inline void refuse(const std::string& why) { throw RequestRefused(why); }

}   // namespace gonio
