// help.h: gonio's help, assembled from the commands (their usage, summary, option tables and notes) and the prose that
// is gonio's as a whole (the title, the exit codes, the conventions).
#pragma once
#include "options.h"

#include <string>
#include <vector>

namespace gonio {

// `gonio --help`: the list of commands, each command's options and notes, the exit codes.
std::string full_help(const std::vector<Command>& all);
// `gonio` without a command: the title, the list of commands and the exit codes.
std::string short_help(const std::vector<Command>& all);
// `gonio COMMAND --help`: the command's usage, every option of its table, its notes, and the exit codes.
std::string command_help(const Command& c);

}   // namespace gonio
