// rgb_vs_spectral.h: gonio compare --rgb-vs-spectral: the stack traced band by band and in RGB (its measured
// materials reduced to three channels by --reduction), and the colour difference of the two per bin and per angle
// (colour_error.h), written beside both runs' files.
#pragma once

#include "measured_materials.h"
#include "case.h"
#include "spectral_bands.h"

namespace gonio {

class VkContext;

// Writes OUT/spectral/ (simulate --spectral's files), OUT/rgb/ (simulate's), OUT/rgb-vs-spectral.json and .csv, and a
// line per angle. Returns the exit code.
int run_rgb_vs_spectral(const Case& run, const SpectralBands& bands, RgbReduction reduction, VkContext& ctx);

}   // namespace gonio
