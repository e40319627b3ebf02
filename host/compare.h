// compare.h: how far each model is from the reference, on the same bins (gonio compare).
#pragma once
#include "models.h"
#include "histogram.h"
#include "reference.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace gonio {

// Per model, incident angle and side, in the seed's remapped space g(f) = log(1 + sqrt f)
// and in linear f, over all bins and channels.
struct ModelMetrics {
    double rmse_remapped = 0, mean_abs_remapped = 0, rmse_linear = 0, mean_rel_linear = 0;
    glm::dvec3 albedo_model{0}, albedo_reference{0};
    double max_abs_remapped = 0;               // the largest |g(model) - g(reference)|
    double max_theta_deg = 0, max_phi_deg = 0; // its bin centre
    int max_channel = 0;
    double reference_noise_remapped = 0;       // RMS over bins of the reference's standard error mapped by g'
    bool within_noise = false;                 // rmse_remapped below twice the reference noise
};

// A model's directional albedo (reflected + transmitted, from its bin averages) above 1 + this breaks the white-
// furnace bound: summary.json flags it (reflects_more_than_it_receives), compare warns.
inline constexpr double kWhiteFurnaceTolerance = 1e-3;

// side: kReflection (model.f) or kTransmission (model.t); the albedo is then the directional transmittance.
ModelMetrics compare_model(const SimResult& ref, size_t angle, const std::vector<glm::dvec3>& model, Side side = kReflection);

// One line on stderr per model and incident angle whose albedo breaks the white-furnace bound, with the model's
// documented reason (model_registry().energy_note).
void warn_energy_gains(const SimResult& ref, const std::vector<ModelSlices>& models);

// The "models" JSON member of summary.json (without the trailing newline).
// stage: what the whole model stage cost ("model_stage" in summary.json), or null
std::string models_json(const SimResult& ref, const std::vector<ModelSlices>& models, const std::vector<ModelCost>& costs,
                        const ModelStageCost* stage = nullptr);

}  // namespace gonio
