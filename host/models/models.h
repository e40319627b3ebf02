// models.h: the analytic layered models gonio compares with the reference, evaluated as bin averages on the
// reference's bins by shaders/models.comp.
#pragma once
#include "reference.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct ModelInfo {
    std::string id;
    std::string citation;
    std::string summary;     // what it does, in one line
    std::string represents;  // which stacks it can represent
    bool reciprocal;         // f(l, v) = f(v, l) by construction (tested both ways)
    bool energy_conserving;  // directional albedo <= 1 for every stack it represents, by construction (tested
                             // on hard stacks); false: the model's construction does not guarantee it
    std::string energy_note; // why not, when not
    uint32_t shader_model = 0;   // the model's code in shaders/lib/models/all.glsl (MODEL_*): a variant shares its
                                 // base model's code
    uint32_t convention = 0;     // CONVENTION_* bits (belcour_tables.glsl): 0 is what the model's official code
                                 // computes; a variant (id base+g2, +tir) sets gonio's alternatives
};

// The models' conventions (ModelInfo::convention bits, CONVENTION_* in shaders/lib/models/belcour_tables.glsl).
constexpr uint32_t MODEL_CONVENTION_G2 = 1;                // height-correlated Smith G2 in lobes and FGD/TIR tables
constexpr uint32_t MODEL_CONVENTION_TIR_BELOW_MEDIA = 2;   // Belcour's TIR term kept below an absorbing medium

const std::vector<ModelInfo>& model_registry();

// "" when model `index` can represent the stack; otherwise why not.
std::string model_cannot_represent(size_t index, const Stack& s);

struct ModelSlices {
    std::string id;
    std::string not_applicable;                  // non-empty: the reason; f is then empty
    std::vector<std::vector<glm::dvec3>> f;      // per incident angle: reflection-side bin averages (1/sr)
    std::vector<std::vector<glm::dvec3>> t;      // per incident angle: transmission side (transmissive stacks
                                                 // and models with a transmitted lobe; else empty)
    // the same shapes as f and t: an estimate of each bin average's integration error (absolute, 1/sr): the
    // graded quadrature's |4x4 - 3x3 Gauss-Legendre| summed over the bin's pieces, without the lobe grids' share
    // (deltas, lobes below float resolution); docs/MODELS.md "Bin integration". Empty when not estimated
    std::vector<std::vector<glm::dvec3>> f_err, t_err;
};

// Switches of the models.
struct ModelOptions {
    bool belcour_tables = true;   // Belcour's models: FGD and TIR tables (false: Fresnel at the mean cosine, no
                                  // TIR term, as the seed runs them for slabs)
};

struct ModelGrid {                               // the bins and angles to evaluate on (those of a reference run)
    uint32_t n_theta, n_phi;
    double dtheta_deg, dphi_deg;
    std::vector<double> theta_i_deg;
};
ModelGrid model_grid(const SimResult& r);

// What evaluating one model cost, over all incident angles.
struct ModelCost {
    double wall_seconds = 0;      // host clock, including the first dispatch's JIT compile
    double device_seconds = 0;    // device timestamps around the model's dispatches
    uint64_t evaluations = 0;     // evaluations of f(l, v) (quadrature nodes and lobe-grid nodes)
};

// What the whole model stage cost (one evaluate() call: every applicable model at every incident angle).
struct ModelStageCost {
    double wall_seconds = 0;        // host clock, the whole call
    double setup_seconds = 0;       // host clock: E_coat and Belcour's tables (computed, or read from the cache)
    double pipeline_seconds = 0;    // host clock: creating the pipelines this call needed (concurrently)
    uint32_t pipelines_created = 0; // how many (0 when an evaluator's earlier call made them)
    double device_seconds = 0;      // the models' device timestamps, summed (with lavapipe's JIT at first dispatches)
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
    const std::vector<float>& belcour_tables(const Stack& s);
    double table_seconds() const;   // device seconds spent computing tables so far
private:
    struct Impl;
    Impl* impl_;
};

// One-shot: a ModelEvaluator for one call.
std::vector<ModelSlices> evaluate_models(VkContext& ctx, const Stack& s, const ModelGrid& grid,
                                         std::vector<ModelCost>* costs = nullptr, const ModelOptions& options = {},
                                         ModelStageCost* stage = nullptr);

// Belcour's tables on the CPU twin (the same code as shaders/tables.comp), layout of belcour_tables.glsl.
std::vector<float> belcour_tables_cpu(const Stack& s);

// Belcour's lobes at incident cosine mu, through the CPU twin: energies, roughnesses, transmitted lobe.
struct BelcourLobesHost {
    std::vector<glm::dvec3> e;
    std::vector<double> alpha;
    glm::dvec3 e_t{0.0};
    double alpha_t = 0.0;
};
// convention: CONVENTION_* bits (0: the official code's conventions).
BelcourLobesHost belcour_lobes_cpu(const Stack& s, double mu, bool tables, uint32_t convention = 0);
// The same with the given tables (e.g. ModelEvaluator::belcour_tables, the device's) in place of the twin's.
BelcourLobesHost belcour_lobes_cpu(const Stack& s, double mu, const std::vector<float>& tables, uint32_t convention = 0);
// A lobe whose roughness a model computes below this is a delta: the models evaluate every lobe below
// MODEL_MIN_ALPHA (1e-4) as GGX at MODEL_MIN_ALPHA, the stand-in of a smooth interface, and a roughness this far
// below it is 0 up to float rounding (e.g. a transmitted lobe's variance through index-matched interfaces, with
// tables whose Fresnel 0 is 1e-7). Its whole mass belongs in the bin of the mirror (or straight-through) direction.
constexpr double kModelDeltaAlpha = 5e-5;
// tm21's lobes (energies and roughnesses; lobe 0 is drawn as the exact top BRDF), through the CPU twin.
BelcourLobesHost tm21_lobes_cpu(const Stack& s, double mu, bool tables, uint32_t convention = 0);
BelcourLobesHost tm21_lobes_cpu(const Stack& s, double mu, const std::vector<float>& tables, uint32_t convention = 0);
// Belcour's roughness <-> linearised variance mapping (the GLSL functions, through the CPU twin).
double belcour_variance_of(double alpha);
double belcour_roughness_of(double sigma);
// Table geometry (shaders/lib/models/belcour_tables.glsl): entry (layer, alpha node a, mu node c) of the set with
// separable Smith G (g2 = false, the default models') or with height-correlated G2 (g2 = true, the +g2 variants).
struct BelcourTableGeometry { uint32_t n_mu, n_alpha; };
BelcourTableGeometry belcour_table_geometry();
double belcour_table_mu(uint32_t c);
double belcour_table_alpha(uint32_t a);
glm::dvec3 belcour_table_fgd(const std::vector<float>& tables, uint32_t layer, uint32_t a, uint32_t c, bool g2 = false);
double belcour_table_tir(const std::vector<float>& tables, uint32_t layer, uint32_t a, uint32_t c, bool g2 = false);

// The directional albedo E(mu) of the stack's top interface (its reflection alone), at mu = i / 64, i = 0..64.
std::vector<float> coat_albedo_table(const Stack& s);

// f(l, v) of one model at one pair of directions (z = normal), through the CPU twin of the shader code.
// v.z < 0: the transmission side (models with a transmitted lobe).
glm::dvec3 model_value_cpu(size_t index, const Stack& s, glm::vec3 l, glm::vec3 v, const ModelOptions& options = {});

// The terms of a model (models/common.glsl TERM_TOP, TERM_BASE): its top-interface reflection (lobe 0) and
// everything that went through the top interface (the lobes below, the transmitted lobe).
constexpr uint32_t kModelTermTop = 1u, kModelTermBase = 2u;

// The same CPU twin for many evaluations of one model on one stack: packs the stack, E_coat and Belcour's tables
// once. value(l, v) computes exactly what model_value_cpu(index, s, l, v, options) does; `terms` selects terms.
// `tables`: Belcour's tables to use instead of the CPU twin's (e.g. ModelEvaluator::belcour_tables, the device's,
// which agree with the twin's to 7.5e-4). Safe to use from several threads at once (each call sets the twin's
// per-thread environment).
class ModelCpu {
public:
    ModelCpu(size_t index, const Stack& s, const ModelOptions& options = {}, const std::vector<float>* tables = nullptr);
    glm::dvec3 value(glm::vec3 l, glm::vec3 v, uint32_t terms = kModelTermTop | kModelTermBase) const;
private:
    size_t index_;
    std::vector<float> coat_albedo_, tables_;
    std::vector<unsigned char> stack_;   // the packed StackGpu (stack_gpu.h), kept opaque here
    bool use_tables_;
};

}  // namespace gonio
