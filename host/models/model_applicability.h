// model_applicability.h: which stacks each model of the registry can represent, and why not the others.
#pragma once
#include "stack.h"

#include <cstddef>
#include <string>

namespace gonio {

// "" when model `index` can represent the stack; otherwise why not.
std::string model_cannot_represent(size_t index, const Stack& s);

}   // namespace gonio
