// cmd_random_stack.h: `gonio random-stack`: seeded random stacks over the whole valid parameter space, as TOML.
#pragma once
#include "args.h"

namespace gonio {

int cmd_random_stack(const Args& a);

}   // namespace gonio
