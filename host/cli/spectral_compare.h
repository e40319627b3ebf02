// spectral_compare.h: gonio compare --spectral: the stack traced band by band (the reference, as simulate --spectral),
// every model that can represent it evaluated on the same bins, the research models band by band (the stack at each
// pass's three wavelengths) and the production models in RGB as they are defined (an artist's colours as inputs), and
// each model's colour difference from the reference per bin and angle (colour_error.h).
#pragma once

#include "measured_materials.h"
#include "model_registry.h"
#include "simulate_run.h"
#include "spectral_bands.h"

namespace gonio {

class VkContext;

// Writes OUT/<name>.exr and OUT/summary.json (the spectral reference), OUT/models-spectral.json, and a line per model.
// Returns the exit code.
// The production models (model_takes_artist_colours) are evaluated once, on the stack reduced to RGB by `reduction`.
int run_spectral_compare(const SimulateRun& run, const SpectralBands& bands, const ModelOptions& models,
                         RgbReduction reduction, VkContext& ctx);

}   // namespace gonio
