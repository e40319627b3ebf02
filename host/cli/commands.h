// commands.h: gonio's commands, each with its options (cmd_NAME.cpp), in the order of `gonio --help`; main runs one,
// and the Python module (host/python) takes its options and help from the same table.
#pragma once
#include "options.h"

#include <string>
#include <vector>

namespace gonio {

const std::vector<Command>& commands();
// The command of that name; throws std::invalid_argument for none.
const Command& command_named(const std::string& name);

}   // namespace gonio
