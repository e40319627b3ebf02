// cmd_random_stack.h: `gonio random-stack`: seeded random stacks over the whole valid parameter space, as TOML.
#pragma once
#include "options.h"

namespace gonio {

Command random_stack_command();

}   // namespace gonio
