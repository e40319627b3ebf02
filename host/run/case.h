// case.h: a case is a stack and the reference run asked of it (its options, its output directory, the run it
// continues); what a command computes on it comes back as a CaseResult (the reference, the models on its bins and
// their comparison, computed once), which write_case writes: the EXR, slices.csv, summary.json, state.gonio and the
// console's lines.
#pragma once
#include "comparison.h"
#include "json.h"
#include "model_evaluator.h"
#include "reference.h"
#include "stack.h"

#include <optional>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct Case {
    Stack stack;
    SimOptions sim;   // checked, the checkpoints written into out
    std::string out;
    std::optional<SimResult> previous;   // --resume DIR: the run it continues
    const SimResult* resumed() const { return previous ? &*previous : nullptr; }
};

// The models on a reference's bins, their cost, and their comparison with it.
struct ModelsOnCase {
    std::vector<ModelSlices> slices;
    std::vector<ModelCost> costs;
    std::optional<ModelStageCost> stage;   // what the whole model stage cost, where it ran as one
    Comparison comparison;
};
// The models' slices compared with the reference (compare_models).
ModelsOnCase models_on_case(const SimResult& ref, std::vector<ModelSlices> slices, std::vector<ModelCost> costs = {},
                            std::optional<ModelStageCost> stage = std::nullopt);

struct CaseResult {
    SimResult reference;
    std::optional<ModelsOnCase> models;   // compare: the models on the reference's bins
};
// The reference of c on the device, and, where `models` is given, those models on its bins compared with it.
CaseResult run_case(VkContext& ctx, const Case& c, const ModelOptions* models);

// Writes the case's files (with the models' rows and metrics where it has models), prints a line per incident angle
// and the models' table. Returns 1 where something could not be used (paths whose weight stopped being finite, a
// model's values, numbers of summary.json), else 0.
int write_case(const Case& c, const CaseResult& r);
// The case's summary.json (with the models' metrics where it has models) and slices.csv, in memory: the bytes
// write_case writes (json_text gives the JSON's).
Json case_summary_json(const CaseResult& r);
std::string case_slices_csv(const CaseResult& r);
// The case's files in out, and nothing on the console: the EXR, slices.csv, summary.json and state.gonio.
void write_case_files(const std::string& out, const CaseResult& r);
// run_case, then write_case: a case from the device to its files, in one call (compare, simulate). Returns
// write_case's status.
int run_and_write_case(VkContext& ctx, const Case& c, const ModelOptions* models);
// The models' files beside a reference (score, fit --reference: no state.gonio, the reference left as it is): the
// EXR, slices.csv and summary.json in out.
void write_models_beside(const std::string& out, const SimResult& ref, const ModelsOnCase& m);

}   // namespace gonio
