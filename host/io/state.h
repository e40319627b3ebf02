// state.h: a run's raw sums on disk (<out>/state.gonio), so that --resume continues it exactly (state.cpp).
#pragma once
#include "reference.h"

#include <string>

namespace gonio {

// The run's state, to continue it later (--resume): the raw sums, energy book and options.
void save_state(const std::string& path, const SimResult& r);
SimResult load_state(const std::string& path);

}   // namespace gonio
