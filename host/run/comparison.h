// comparison.h: every model against the reference, computed once per run: each scored model's metrics and verdict
// per incident angle and side (compare_model), the best model of each slice, each model's total albedo. What prints
// or writes a model's score (summary.json, the console's table, sweep.csv, fit.json, bench) reads it here.
#pragma once
#include "compare.h"

#include <vector>

namespace gonio {

// One model's scores on the run's slices; empty for a model that was not scored (model_has_bins false).
struct ModelScores {
    std::vector<ModelMetrics> r, t;   // per incident angle: reflection; transmission where the model has that side
    std::vector<glm::dvec3> total_albedo;   // per incident angle: reflected + transmitted
    LargestAlbedo largest;   // the largest of total_albedo over angles and channels
    const std::vector<ModelMetrics>& side(Side s) const { return s == kReflection ? r : t; }
};

struct Comparison {
    std::vector<ModelScores> models;   // one per model, in the order of the models compared
    std::vector<BestModel> best[2];   // per side (kReflection, kTransmission) and incident angle
    const BestModel& best_of(size_t angle, Side side) const;   // an empty one where the run has no such slice
};

// Each model's metrics (with its bin integration error, where estimated), the best model per slice and the albedos.
Comparison compare_models(const SimResult& ref, const std::vector<ModelSlices>& models);

// One line on stderr per model and incident angle whose albedo breaks the white-furnace bound, with what the model
// claims (its header's energy-conserving, and its reason).
void warn_energy_gains(const SimResult& ref, const std::vector<ModelSlices>& models, const Comparison& c);

}   // namespace gonio
