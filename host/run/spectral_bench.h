// spectral_bench.h: gonio bench --spectral: per stack, a spectral run and an RGB run of the same paths at the bench's
// angle, and what each costs to reach a given median relative standard error in X, Y and Z.
#pragma once

#include "reference.h"
#include "spectral_bands.h"
#include "vk_context.h"

#include <string>
#include <vector>

namespace gonio {

// Prints a line per stack: each run's seconds, its median rse in X, Y and Z and its seconds to 1% (rse^2 t / 0.01^2),
// and the spectral run's cost at equal error (the largest over X, Y, Z). Returns the exit code.
int run_spectral_bench(const std::vector<std::string>& stacks, const SimOptions& sim, const ContextOptions& ctx_opt,
                       const SpectralBands& bands);

}   // namespace gonio
