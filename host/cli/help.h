// help.h: gonio's help texts, in sections: `gonio --help` prints them all, `gonio COMMAND --help` the command's own.
#pragma once
#include <string>

namespace gonio {

// `gonio --help`: every section.
std::string full_help();
// `gonio` without a command: the title, the usage lines and the exit codes.
std::string short_help();
// `gonio COMMAND --help`: the command's usage lines and options, and the exit codes.
std::string command_help(const std::string& cmd);

}   // namespace gonio
