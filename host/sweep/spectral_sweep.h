// spectral_sweep.h: a sweep with a [spectral] table (docs/SWEEPS.md): each configuration traced band by band as
// compare --spectral traces it, its models' colour errors and its RGB run's (its measured materials reduced to three
// channels) as rows of sweep.csv (kSpectralSweepColumns), sharded, resumed and merged as every sweep is.
#pragma once

#include "sweep.h"

namespace gonio {

class VkContext;

// Runs the configurations of one shard into DIR/configs/; returns how many it computed (not skipped).
uint64_t run_spectral_sweep(VkContext& ctx, const Sweep& s, const std::string& dir, const SweepRunOptions& o);

}   // namespace gonio
