// state.h: a run's raw sums on disk (<out>/state.gonio), so that --resume continues it exactly (state.cpp).
#pragma once
#include "reference.h"

#include <string>

namespace gonio {

// The run's state, to continue it later (--resume): the raw sums, energy book and options.
void save_state(const std::string& path, const SimResult& r);
SimResult load_state(const std::string& path);
// Throws std::invalid_argument naming what differs if `previous` cannot be continued by a run of
// (stack, opt).
void check_resumable(const SimResult& previous, const Stack& stack, const SimOptions& opt);

}   // namespace gonio
