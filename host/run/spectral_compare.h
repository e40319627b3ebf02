// spectral_compare.h: gonio compare --spectral: the stack traced band by band (the reference, as simulate --spectral),
// every model that can represent it evaluated on the same bins, the research models band by band (the stack at each
// pass's three wavelengths) and the production models in RGB as they are defined (an artist's colours as inputs), and
// each model's colour difference from the reference per bin and angle (colour_error.h).
#pragma once

#include "colour_error.h"
#include "measured_materials.h"
#include "model_registry.h"
#include "case.h"
#include "spectral_bands.h"

namespace gonio {

class VkContext;
class ModelEvaluator;

// One model's colours against a spectral reference: per angle and side where it has bins, its colour error (slices in
// the reference's angle order, reflection before transmission); `why` where it cannot be evaluated (not applicable,
// or unusable at some band). in_rgb: a production model (model_takes_artist_colours) evaluated once in RGB.
struct SpectralModelColours {
    std::string id, why;
    bool in_rgb = false;
    std::vector<ColourErrorSlice> slices;
};
// Every selected model on the spectral run's bins: the research models band by band (the stack at each pass's
// wavelengths), the production models on the stack reduced to RGB by `reduction` (what it clipped in `clipped`).
std::vector<SpectralModelColours> spectral_model_colours(const SpectralResult& spectral, const Stack& stack,
                                                         const ModelOptions& models, RgbReduction reduction,
                                                         ModelEvaluator& evaluator, bool progress,
                                                         std::string& clipped);
// How the model was evaluated, as models-spectral.json and a spectral sweep say it.
std::string spectral_model_evaluation(const SpectralModelColours& m, RgbReduction reduction);

// Writes OUT/<name>.exr and OUT/summary.json (the spectral reference), OUT/models-spectral.json, and a line per model.
// Returns the exit code.
// The production models (model_takes_artist_colours) are evaluated once, on the stack reduced to RGB by `reduction`.
int run_spectral_compare(const Case& run, const SpectralBands& bands, const ModelOptions& models,
                         RgbReduction reduction, VkContext& ctx);

}   // namespace gonio
