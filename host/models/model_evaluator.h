// model_evaluator.h: the analytic models evaluated as bin averages on the reference's bins by shaders/models.comp:
// the dispatches of each model's pipeline at each incident angle, and what they cost.
#pragma once
#include "model_registry.h"
#include "model_reciprocity.h"
#include "reference.h"

#include <glm/glm.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct ModelSlices {
    std::string id;
    std::string not_applicable;   // non-empty: the reason; f is then empty
    bool not_selected = false;   // the reason is --models (compare prints those in one line)
    std::vector<std::vector<glm::dvec3>> f;   // per incident angle: reflection-side bin averages (1/sr)
    std::vector<std::vector<glm::dvec3>> t;   // per incident angle: transmission side (transmissive stacks
        // and models with a transmitted lobe; else empty)
    // the same shapes as f and t: an estimate of each bin average's integration error (absolute, 1/sr): the
    // graded quadrature's |4x4 - 3x3 Gauss-Legendre| summed over the bin's pieces, without the lobe grids' share
    // (deltas, lobes below float resolution); docs/MODELS.md "Bin integration". Empty when not estimated
    std::vector<std::vector<glm::dvec3>> f_err, t_err;
    // Values that cannot be used: quadrature nodes where the model returned NaN, an infinity or a negative value
    // (the bins that hold them: invalid_bins), and bins whose quadrature lavapipe's loop limiter cut short. Either
    // sets `invalid` (why), and compare then reports the model instead of scoring it.
    struct BinRef {
        uint32_t angle, side, bin;   // incident-angle index, 0 reflection / 1 transmission, bin index (theta-major)
    };
    uint64_t invalid_nodes = 0;
    std::vector<BinRef> invalid_bins;
    std::vector<BinRef> cut_short_bins;
    // a user's model_lobes gave an unusable lobe (NaN or infinite direction, negative roughness, more than 8): the
    // incident angles and sides (bin 0)
    std::vector<BinRef> invalid_hints;
    // a black box whose narrowest lobe (announced by model_lobes, else assumed: the stack's narrowest interface) is
    // narrower in v than float resolves (model_plan.h kFloatUnresolved): its quadrature cannot be trusted there, and
    // the model is refused (the incident angles and sides, bin 0)
    std::vector<BinRef> float_unresolved;
    std::string invalid;
    // how the model was integrated: "planned" (a built-in's terms, model_plan.cpp) or "black box" (a user's model:
    // the stack's narrowest roughness at the mirror direction, refined where the nodes disagree)
    std::string integration = "planned";   // or "black box with lobe hints" (the file's model_lobes)
    uint32_t refined_bins = 0;   // black box: bin-angle-sides integrated on finer pieces
    uint32_t unrefined_bins = 0;   // black box: ... that needed finer pieces than lavapipe's loop limiter allows
    std::string file;   // a user's model: its file
    // What the model's header claims (-1: it does not say, as a user's file may leave out), and, for a user's model,
    // its reciprocity as gonio measured it (model_reciprocity.h)
    int claims_reciprocal = -1, claims_energy_conserving = -1;
    std::string energy_note;   // the header's reason, if given
    ModelAsymmetry reciprocity;
};

// Whether a model's bins are scored and written: it represents the stack, runs, and every value could be used.
inline bool model_has_bins(const ModelSlices& m) { return m.not_applicable.empty() && m.invalid.empty(); }

struct ModelGrid {   // the bins and angles to evaluate on (those of a reference run)
    uint32_t n_theta, n_phi;
    double dtheta_deg, dphi_deg;
    std::vector<double> theta_i_deg;
    double phi_i_deg = 0.0;   // the incident azimuth of every angle (SimOptions::phi_i_deg), degrees in [0, 360)
};
ModelGrid model_grid(const SimResult& r);

// What evaluating one model cost, over all incident angles.
struct ModelCost {
    double wall_seconds = 0;   // host clock, including the first dispatch's JIT compile
    double device_seconds = 0;   // device timestamps around the model's dispatches
    uint64_t evaluations = 0;   // evaluations of f(l, v) (quadrature nodes and lobe-grid nodes)
    double compile_seconds = 0;   // a user's model: reading, checking and compiling its file (host clock)
};

// What the whole model stage cost (one evaluate() call: every applicable model at every incident angle).
struct ModelStageCost {
    double wall_seconds = 0;   // host clock, the whole call
    double setup_seconds = 0;   // host clock: E_coat and Belcour's tables (computed, or read from the cache)
    double pipeline_seconds = 0;   // host clock: creating the pipelines this call needed (concurrently)
    uint32_t pipelines_created = 0;   // how many (0 when an evaluator's earlier call made them)
    double user_compile_seconds = 0;   // the users' model files: reading, checking and compiling them
    double device_seconds = 0;   // the models' device timestamps, summed (with lavapipe's JIT at first dispatches)
};

// Evaluates models on grids, keeping its pipelines (compiled once, at the first evaluation: lavapipe JIT-compiles
// then) and Belcour's tables (per set of interfaces) between calls: for the viewer and sweeps.
class ModelEvaluator {
public:
    explicit ModelEvaluator(VkContext& ctx);
    ~ModelEvaluator();
    ModelEvaluator(const ModelEvaluator&) = delete;
    ModelEvaluator& operator=(const ModelEvaluator&) = delete;
    // Every model in the registry on the grid, with what each cost.
    std::vector<ModelSlices> evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs = nullptr,
                                      const ModelOptions& options = {}, ModelStageCost* stage = nullptr);
    // Belcour's FGD and TIR tables for the stack's interfaces, computed on the device (cached).
    const std::vector<float>& belcour_tables(const StackGpu& sg);
    double table_seconds() const;   // device seconds spent computing tables so far
private:
    struct Impl;
    Impl* impl_;
};

// One-shot: a ModelEvaluator for one call.
std::vector<ModelSlices> evaluate_models(VkContext& ctx, const Stack& s, const ModelGrid& grid,
                                         std::vector<ModelCost>* costs = nullptr, const ModelOptions& options = {},
                                         ModelStageCost* stage = nullptr);

}   // namespace gonio
