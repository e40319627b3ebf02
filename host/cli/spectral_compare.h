// spectral_compare.h: gonio compare --spectral: the stack traced band by band (the reference, as simulate --spectral),
// every model that can represent it evaluated band by band on the same bins (the stack at each pass's three
// wavelengths), and each model's colour difference from the reference per bin and angle (colour_error.h).
#pragma once

#include "model_registry.h"
#include "simulate_run.h"
#include "spectral_bands.h"

namespace gonio {

class VkContext;

// Writes OUT/<name>.exr and OUT/summary.json (the spectral reference), OUT/models-spectral.json, and a line per model.
// Returns the exit code.
int run_spectral_compare(const SimulateRun& run, const SpectralBands& bands, const ModelOptions& models,
                         VkContext& ctx);

}   // namespace gonio
