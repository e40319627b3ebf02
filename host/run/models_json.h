// models_json.h: the models' members of summary.json (gonio compare, score, sweep --keep-results): each model's
// metrics and verdict per incident angle and side, why a model was not scored or does not apply, the best model.
#pragma once
#include "comparison.h"
#include "json.h"

#include <vector>

namespace gonio {

// The verdict's members of a model's entry in summary.json (chi2_per_dof ... verdict), as a JSON object.
Json agreement_json(const Agreement& a);
// summary.json's "best_model": per side and incident angle, the best model, the runner-up and whether they tie.
Json best_models_json(const SimResult& ref, const Comparison& c);
// The models' members of summary.json ("model_stage", "best_model", "models"), as a JSON object: the models' scores
// as `c` holds them. stage: what the whole model stage cost ("model_stage" in summary.json), or null
Json models_json(const SimResult& ref, const std::vector<ModelSlices>& models, const Comparison& c,
                 const std::vector<ModelCost>& costs, const ModelStageCost* stage = nullptr);

}   // namespace gonio
