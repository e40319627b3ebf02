// stack_gpu.h: a parsed Stack turned into what the walk reads (uniform block and specialisation).
#pragma once
#include "cpu_twin.h"
#include "stack.h"

namespace gonio {

StackGpu pack_stack(const Stack& s);
// specialised = false gives the general N-layer walk (everything read from the uniform block).
WalkSpec walk_spec(const Stack& s, bool specialised);

}  // namespace gonio
