// cmd_check.h: `gonio check STACK.toml`: parse and validate a stack file, print it and the walk simulate runs on it.
#pragma once
#include "args.h"

namespace gonio {

int cmd_check(const Args& a);

}   // namespace gonio
