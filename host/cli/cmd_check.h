// cmd_check.h: `gonio check STACK.toml`: parse and validate a stack file, print it and the walk simulate runs on it.
#pragma once
#include "options.h"

namespace gonio {

Command check_command();

}   // namespace gonio
