// spectral_simulate.h: gonio simulate --spectral: the stack traced band by band (three bands per pass of the RGB
// walk, each band at its centre wavelength), its files (spectral_output.h) and a line per angle.
#pragma once

#include "case.h"
#include "spectral_bands.h"
#include "spectral_output.h"

namespace gonio {

class VkContext;

// The stack traced band by band with the run's options (pass g with seed + g; on the device every pass side by side
// in one batch, simulate_gpu_batch); ctx null: the CPU twin. rc becomes 1 where a path's weight stopped being finite.
// Refuses (exit 2) a stack that cannot be traced spectrally, --resume and --max-seconds.
SpectralResult trace_spectral(const Case& run, const SpectralBands& bands, VkContext* ctx, unsigned threads, int& rc);

// ctx null: the CPU twin with `threads` threads. A stack that cannot be traced spectrally (spectral_refusal) is
// refused with exit 2. Returns the exit code (1 where a path's weight stopped being finite).
int run_spectral_simulate(const Case& run, const SpectralBands& bands, VkContext* ctx, unsigned threads);

}   // namespace gonio
