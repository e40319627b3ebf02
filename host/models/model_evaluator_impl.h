// model_evaluator_impl.h: the inside of ModelEvaluator (model_evaluator.cpp: the planned built-in models;
// model_black_box.cpp: a model integrated as a black box; model_quadrature_outputs.cpp: models.comp's outputs and
// push constants). Not for other files.
#pragma once
#include "belcour_tables_host.h"
#include "compute_kernel.h"
#include "model_evaluator.h"
#include "model_plan.h"
#include "model_stack.h"
#include "user_model.h"

#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

namespace gonio {

// Bin b's quadrature outputs: nodes where the model's value could not be used, and a quadrature the loop limiter cut
// short, booked on the model.
void note_invalid(ModelSlices& ms, const QuadBin& q, uint32_t angle, uint32_t side, uint32_t bin);
// "" where every value can be used, else why not, with where (the first bins).
std::string describe_invalid(const ModelSlices& ms, const ModelGrid& grid);
// The projected solid angle of the bins in theta ring t (sr), as the lobe grids' sums are divided by it
double ring_projected_omega(const ModelGrid& grid, uint32_t t);
// The push constants of models.comp's quadrature at incident angle theta (degrees) and side for `terms` whose
// narrowest lobe has roughness `narrowest` (0: none); coat_model: a two-layer model's terms (the base terms stop at
// the critical angle of a coat of lower index).
ModelPush quadrature_push(uint32_t terms, const ModelGrid& grid, double theta, int side, const ModelStack& mstack,
                          double narrowest, bool coat_model, uint32_t max_rects, bool tables);

// Bytes per bin of the lobe grids' 64-bit sums; a user's delta lobes as models.comp books them (GONIO_MODEL_HINTS):
// a count, then (weight, bin) per lobe
constexpr size_t kLobeBytes = LOBE_SUMS_PER_BIN * sizeof(int64_t);
constexpr size_t kDeltaBytes = (1 + GONIO_MAX_HINTS) * 4 * sizeof(float);

// A pipeline of models.comp: which kernel (MODEL_KERNEL_*) of which registry entry.
using KernelKey = std::pair<uint32_t, uint32_t>;

struct ModelEvaluator::Impl {
    VkContext& ctx;
    ModelStackBuffers inputs;   // the stack, E_coat, Belcour's tables
    Buffer lobes;   // KERNEL 2's lobes; a user's delta lobes
    Buffer quad, lobe, host;   // per bin: the quadrature's QuadBin, the lobe grids' sums; their host copy
    size_t nb = 0;   // bins the grid buffers hold
    std::map<KernelKey, std::unique_ptr<ComputeKernel>> kernels;   // built when first needed
    std::map<const UserModel*, std::unique_ptr<ComputeKernel>> user_kernels;   // users' models' quadrature kernels
    // a user's model's slot of parameters (MODEL_USER_PARAMETER_SLOT0 + its place in the options' user_models): its
    // kernels' MODEL specialisation constant, which models/stack_tables.glsl model_parameter reads
    std::map<const UserModel*, uint32_t> user_slots;
    void assign_user_slots(const ModelOptions& options);
    BelcourTableKernel table_kernel;   // Belcour's tables for the stacks seen (and on disk)
    vk::raii::QueryPool queries = nullptr;
    // Submissions of the model kernels since their pipelines were made. lavapipe (Mesa 22.3) keeps memory for every
    // dispatch until the pipeline that ran it is destroyed (measured: 4.8 MB per evaluation of one quadrature model
    // at 4 angles, 8.4 GB over a 64-configuration sweep with fits), so evaluate() makes them anew after
    // kRenewPipelinesAfter submissions (about 300 MB; a renewal costs about 20 ms per model's pipelines)
    static constexpr uint32_t kRenewPipelinesAfter = 256;
    uint32_t submissions = 0;
    void renew_pipelines_if_due();
    // Whether the pipelines integrate bins at an incident azimuth (MODEL_SPEC_INCIDENT_AZIMUTH): the grid's, whose
    // change makes them anew
    bool azimuth = false;
    void use_azimuth(const ModelGrid& grid);
    // models.comp's specialisation constants: kernel, model (or a user's slot), conventions, azimuth (4 bytes each)
    static std::vector<vk::SpecializationMapEntry> model_spec_entries();

    explicit Impl(VkContext& c);
    void ensure_grid(size_t bins);
    static std::vector<vk::DescriptorType> model_descriptor_types();
    std::vector<const Buffer*> buffers() const;
    std::vector<const Buffer*> point_buffers() const;   // buffers(), the points in place of the lobes (KERNEL 3)
    double
    device_seconds();   // between the two timestamps of the last recording   // models.comp's, indexed by binding (MODEL_BINDING_*)
    std::unique_ptr<ComputeKernel> make_kernel(KernelKey key);
    ComputeKernel& kernel(uint32_t which, uint32_t model);
    uint32_t prepare(const std::set<KernelKey>& need);   // the pipelines not made yet, concurrently

    // plan -> record -> read back: every model of the registry, then the users'
    std::vector<ModelSlices> evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs,
                                      const ModelOptions& options, ModelStageCost* stage);
    // a planned model's terms at one incident angle and side: its dispatches, timed
    void record_planned(vk::CommandBuffer c, uint32_t m, const std::vector<TermPlan>& terms, const ModelPush& pc,
                        double theta, const ModelGrid& grid);
    // the bin averages those dispatches left (quadrature plus the lobe grids' sums) and their error estimates
    void read_planned(ModelSlices& ms, ModelCost& cost, const std::vector<TermPlan>& terms, bool quadrature,
                      size_t angle, int side, const ModelGrid& grid);

    // ---- a model integrated as a black box (model_black_box.cpp; docs/MODELS.md "Your own model") ----
    std::unique_ptr<ComputeKernel> make_user_kernel(const UserModel& um, uint32_t which = MODEL_KERNEL_QUADRATURE);
    // users' models' KERNEL 3 (their values at direction pairs), and the buffer of the pairs it is bound to
    std::map<const UserModel*, std::unique_ptr<ComputeKernel>> user_point_kernels;
    Buffer points;
    // f(l, v) against f(v, l) at reciprocity_directions() (model_reciprocity.h), on the stack uploaded last
    ModelAsymmetry measure_reciprocity(const UserModel& um, ModelCost& cost);
    struct QuadOut {   // one quadrature dispatch's outputs per bin
        std::vector<glm::dvec3> f, err;
        std::vector<QuadBin> raw;   // as models.comp wrote them
        std::vector<glm::vec4> deltas;   // with_deltas: a user's delta lobes on this side, (weight, bin)
    };
    // One quadrature dispatch (every bin, or the 64-bin blocks listed) and its outputs per bin.
    QuadOut run_quadrature(ComputeKernel& k, ModelPush pc, size_t nb, const std::vector<uint32_t>* blocks,
                           ModelCost& cost, bool with_deltas = false);
    ModelSlices evaluate_black_box(const UserModel& um, const ModelStack& mstack, const ModelGrid& grid,
                                   const ModelOptions& options, ModelCost& cost, ModelStageCost& sc);
    // The black box's quadrature into ms with kernel k (a user's model, or a built-in model with no plan).
    // hints: the model announces its lobes (model_lobes), which the device checks instead of the stack's roughness
    void integrate_black_box(ModelSlices& ms, ComputeKernel& k, const ModelStack& mstack, const ModelGrid& grid,
                             ModelCost& cost, bool hints);
    // one incident angle and side of it: the levels of refinement
    void integrate_black_box_at(ModelSlices& ms, ComputeKernel& k, ModelPush pc, size_t angle, int side,
                                const ModelGrid& grid, ModelCost& cost, bool hints);
};

}   // namespace gonio
