// model_evaluator.cpp: ModelEvaluator, the planned built-in models: what the stack implies for them (model_stack.h),
// each model's plan per incident angle and side (model_plan.h), the pipelines they need, then per angle and side the
// recorded dispatches (Belcour's lobes, the graded quadrature, the lobe grids) and the bin averages read back.
#include "model_evaluator_impl.h"
#include "model_twin.h"
#include "models_spv_table.h"   // generated (CMakeLists.txt): models_N_spv.h, one per built-in model file

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace gonio {

namespace {

// models.comp, one SPIR-V module per built-in model file (CMakeLists.txt: GONIO_MODEL_ONLY), by code
struct ModelSpv {
    const uint32_t* code;
    size_t bytes;
};
const ModelSpv kModelSpv[] = {GONIO_MODELS_SPV};

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Each model's terms per incident angle and side (in that order), and the pipelines they need.
struct Plans {
    std::vector<std::vector<std::vector<TermPlan>>> terms;   // [model][angle * sides + side]
    std::set<KernelKey> need;
};

}   // namespace

ModelGrid model_grid(const SimResult& r) {
    return {r.n_theta, r.n_phi, r.options.dtheta_deg, r.options.dphi_deg, r.options.theta_i_deg, r.options.phi_i_deg};
}

ModelEvaluator::Impl::Impl(VkContext& c) : ctx(c), inputs(c), table_kernel(c) {
    std::memset(inputs.tables.mapped, 0, TABLE_FLOATS * 4);
    lobes = ctx.make_device_buffer(BELCOUR_MU_NODES * BELCOUR_LOBE_STRIDE * sizeof(vec4),
                                   vk::BufferUsageFlagBits::eStorageBuffer);
    queries = vk::raii::QueryPool(ctx.device(),
                                  vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
}

void ModelEvaluator::Impl::ensure_grid(size_t bins) {
    if (bins <= nb) return;
    auto& dev = ctx.device();
    nb = bins;
    quad = ctx.make_device_buffer(nb * sizeof(QuadBin), vk::BufferUsageFlagBits::eStorageBuffer);
    lobe = ctx.make_device_buffer(nb * kLobeBytes, vk::BufferUsageFlagBits::eStorageBuffer);
    host = ctx.make_buffer(nb * (sizeof(QuadBin) + kLobeBytes) + kDeltaBytes, vk::BufferUsageFlagBits::eTransferDst,
                           false);
    for (auto& [key, k] : kernels) k->bind(dev, buffers());
    for (auto& [um, k] : user_kernels) k->bind(dev, buffers());
    for (auto& [um, k] : user_point_kernels) k->bind(dev, point_buffers());
}

std::vector<vk::DescriptorType> ModelEvaluator::Impl::model_descriptor_types() {
    std::vector<vk::DescriptorType> t(MODEL_BINDINGS, vk::DescriptorType::eStorageBuffer);
    t[MODEL_BINDING_STACK] = vk::DescriptorType::eUniformBuffer;
    return t;
}

std::vector<const Buffer*> ModelEvaluator::Impl::buffers() const {
    std::vector<const Buffer*> b(MODEL_BINDINGS, nullptr);
    b[MODEL_BINDING_STACK] = &inputs.stack;
    b[MODEL_BINDING_QUADRATURE] = &quad;
    b[MODEL_BINDING_LOBE_SUMS] = &lobe;
    b[MODEL_BINDING_STACK_TABLES] = &inputs.stack_tables;
    b[MODEL_BINDING_BELCOUR_TABLES] = &inputs.tables;
    b[MODEL_BINDING_BELCOUR_LOBES] = &lobes;
    return b;
}

std::vector<const Buffer*> ModelEvaluator::Impl::point_buffers() const {
    std::vector<const Buffer*> b = buffers();
    b[MODEL_BINDING_BELCOUR_LOBES] = &points;   // KERNEL 3's direction pairs in and values out
    return b;
}

double ModelEvaluator::Impl::device_seconds() {
    auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                 vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
    return double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
}

// the kernel `key.first` of registry entry `key.second`: its base model's module specialised with its conventions
std::unique_ptr<ComputeKernel> ModelEvaluator::Impl::make_kernel(KernelKey key) {
    const auto [which, model] = key;
    const uint32_t code = shader_model_of(model), convention = model_registry().at(model).convention;
    if (code >= std::size(kModelSpv))
        throw std::runtime_error("models.comp: no SPIR-V module for model " + std::to_string(code));
    auto& dev = ctx.device();
    auto k = std::make_unique<ComputeKernel>(dev, kModelSpv[code].code, kModelSpv[code].bytes, model_descriptor_types(),
                                             uint32_t(sizeof(ModelPush)));
    const uint32_t spec[4] = {which, code, convention, azimuth ? 1u : 0u};
    k->build(dev, model_spec_entries(), spec, sizeof spec);
    k->bind(dev, buffers());
    return k;
}

ComputeKernel& ModelEvaluator::Impl::kernel(uint32_t which, uint32_t model) {
    auto& k = kernels[{which, model}];
    if (!k) k = make_kernel({which, model});
    return *k;
}

void ModelEvaluator::Impl::assign_user_slots(const ModelOptions& options) {
    for (size_t k = 0; k < options.user_models.size(); ++k) {
        const UserModel* um = options.user_models[k].get();
        const uint32_t slot = MODEL_USER_PARAMETER_SLOT0 + uint32_t(k);
        const auto it = user_slots.find(um);
        if (it != user_slots.end() && it->second != slot) {   // its kernels were specialised for another slot
            user_kernels.erase(um);
            user_point_kernels.erase(um);
        }
        user_slots[um] = slot;
    }
}

std::vector<vk::SpecializationMapEntry> ModelEvaluator::Impl::model_spec_entries() {
    return {{MODEL_SPEC_KERNEL, 0, 4},
            {MODEL_SPEC_MODEL, 4, 4},
            {MODEL_SPEC_CONVENTION, 8, 4},
            {MODEL_SPEC_INCIDENT_AZIMUTH, 12, 4}};
}

void ModelEvaluator::Impl::use_azimuth(const ModelGrid& grid) {
    if ((grid.phi_i_deg != 0.0) == azimuth) return;
    azimuth = grid.phi_i_deg != 0.0;
    kernels.clear();
    user_kernels.clear();
    user_point_kernels.clear();
}

void ModelEvaluator::Impl::renew_pipelines_if_due() {
    if (submissions < kRenewPipelinesAfter) return;
    kernels.clear();
    user_kernels.clear();
    user_point_kernels.clear();
    submissions = 0;
}

uint32_t ModelEvaluator::Impl::prepare(const std::set<KernelKey>& need) {
    std::vector<KernelKey> todo;
    for (auto& key : need)
        if (!kernels.count(key) || !kernels[key]) todo.push_back(key);
    std::vector<std::unique_ptr<ComputeKernel>> made(todo.size());
    make_concurrently(todo.size(), [&](size_t i) { made[i] = make_kernel(todo[i]); });
    for (size_t i = 0; i < todo.size(); ++i) kernels[todo[i]] = std::move(made[i]);
    return uint32_t(todo.size());
}

namespace {

// a built-in model with no plan (model_plan.h PlanKind::BlackBox) is integrated as a black box, as a user's
bool as_black_box(size_t m, const ModelOptions& options) {
    const auto& bb = options.as_black_box;
    return plan_kind(shader_model_of(m)) == PlanKind::BlackBox ||
           std::find(bb.begin(), bb.end(), model_registry()[m].id) != bb.end();
}

// Every model's plan at every angle and side, and the pipelines they need (only those).
Plans plan_models(const ModelStack& ms, const ModelGrid& grid, const ModelOptions& options) {
    const int sides = ms.stack.transmissive() ? 2 : 1;
    Plans p;
    p.terms.resize(model_registry().size());
    for (size_t m = 0; m < model_registry().size(); ++m) {
        if (!ms.skipped[m].empty()) continue;
        if (as_black_box(m, options)) {
            p.need.insert({MODEL_KERNEL_QUADRATURE, uint32_t(m)});
            continue;
        }
        const bool tables = uses_tables(m) && options.belcour_tables;
        if (uses_tables(m)) p.need.insert({MODEL_KERNEL_LOBES, uint32_t(m)});
        for (double theta : grid.theta_i_deg)
            for (int side = 0; side < sides; ++side) {
                // the tables the device uses: planning looks at the lobes they give
                p.terms[m].push_back(plan(shader_model_of(m), ms, theta, side, tables, model_registry()[m].convention));
                for (auto& t : p.terms[m].back())
                    p.need.insert({t.alpha_grid == 0 ? MODEL_KERNEL_QUADRATURE : MODEL_KERNEL_LOBE_GRID, uint32_t(m)});
            }
    }
    return p;
}

// The terms the graded quadrature integrates, and the narrowest of their lobes (0: none)
uint32_t quadrature_terms(const std::vector<TermPlan>& terms, double& narrowest) {
    uint32_t quad_terms = 0;
    narrowest = 0.0;
    for (auto& t : terms)
        if (t.alpha_grid == 0) {
            quad_terms |= t.term;
            if (t.alpha_eff > 0.0) narrowest = narrowest > 0.0 ? std::min(narrowest, t.alpha_eff) : t.alpha_eff;
        }
    return quad_terms;
}

}   // namespace

void ModelEvaluator::Impl::record_planned(vk::CommandBuffer c, uint32_t m, const std::vector<TermPlan>& terms,
                                          const ModelPush& pc, double theta, const ModelGrid& grid) {
    const size_t bins = size_t(grid.n_theta) * grid.n_phi;
    c.resetQueryPool(*queries, 0, 2);
    c.fillBuffer(*quad.buffer, 0, VK_WHOLE_SIZE, 0);
    c.fillBuffer(*lobe.buffer, 0, VK_WHOLE_SIZE, 0);
    barrier_transfer_to_compute(c);
    c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
    if (uses_tables(m)) {   // Belcour's lobes for this angle, once (models.comp KERNEL 2)
        const bool table = plan_kind(shader_model_of(m)) == PlanKind::LobesSymmetric;
        kernel(MODEL_KERNEL_LOBES, m).record(c, pc, table ? groups_for(BELCOUR_MU_NODES, MODEL_GROUP_SIZE) : 1);
        barrier_compute_to_compute(c);
    }
    if (pc.terms) kernel(MODEL_KERNEL_QUADRATURE, m).record(c, pc, groups_for(bins, MODEL_GROUP_SIZE));
    for (auto& t : terms) {
        if (t.alpha_grid == 0) continue;
        // the lobe's own grid and a wide one, combined by the balance heuristic (a delta: its own only)
        for (int pass = 0; pass < (t.delta ? 1 : 2); ++pass) {
            ModelPush lp = pc;
            lp.terms = t.term;
            lp.alpha_grid = float(pass == 0 ? t.alpha_grid : kWideGrid);
            lp.alpha_partner = t.delta ? 0.0f : float(pass == 0 ? kWideGrid : t.alpha_grid);
            lp.delta = t.delta ? 1u : 0u;
            lp.grid_eta = float(t.grid_eta);
            // the wide grid carries the tails only: half the nodes per side of the lobe's own
            const GridShape gs = lobe_grids(theta, grid.n_phi);
            lp.grid = pass == 0 ? gs.cols : gs.wide_cols;
            lp.grid_rows = pass == 0 ? gs.rows : gs.wide_rows;
            lp.partner_nodes = pass == 0 ? gs.wide_cols * gs.wide_rows : gs.cols * gs.rows;
            kernel(MODEL_KERNEL_LOBE_GRID, m)
                .record(c, lp,
                        groups_for(size_t(lp.grid) * lp.grid_rows, LOBE_GRID_NODES_PER_INVOCATION * MODEL_GROUP_SIZE));
            barrier_compute_to_compute(c);
        }
    }
    c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
    barrier_compute_to_transfer(c);
    c.copyBuffer(*quad.buffer, *host.buffer, vk::BufferCopy{0, 0, bins * sizeof(QuadBin)});
    c.copyBuffer(*lobe.buffer, *host.buffer, vk::BufferCopy{0, bins * sizeof(QuadBin), bins * kLobeBytes});
    barrier_transfer_to_host(c);
}

void ModelEvaluator::Impl::read_planned(ModelSlices& ms, ModelCost& cost, const std::vector<TermPlan>& terms,
                                        bool quadrature, size_t angle, int side, const ModelGrid& grid) {
    cost.device_seconds += device_seconds();
    const double theta = grid.theta_i_deg[angle];
    for (auto& t : terms)
        if (t.alpha_grid != 0) {
            const GridShape gs = lobe_grids(theta, grid.n_phi);
            cost.evaluations += uint64_t(gs.cols) * gs.rows + (t.delta ? 0 : uint64_t(gs.wide_cols) * gs.wide_rows);
        }
    // per bin: the quadrature's RGB bin average and its error estimate, plus the lobe grids' sums over the bin's
    // projected solid angle
    const size_t bins = size_t(grid.n_theta) * grid.n_phi;
    const auto* q = static_cast<const QuadBin*>(host.mapped);
    const auto* lb = reinterpret_cast<const int64_t*>(static_cast<const char*>(host.mapped) + bins * sizeof(QuadBin));
    std::vector<glm::dvec3> f(bins), fe(bins);
    for (size_t b = 0; b < bins; ++b) {
        const double omega = ring_projected_omega(grid, uint32_t(b / grid.n_phi));
        for (int c = 0; c < kChannels; ++c) {
            f[b][c] = double(q[b].f[c]) + double(lb[b * LOBE_SUMS_PER_BIN + c]) / double(LOBE_SCALE) / omega;
            fe[b][c] = double(q[b].err[c]);
        }
        if (quadrature) {
            cost.evaluations += uint64_t(std::max(0.0f, q[b].nodes));
            note_invalid(ms, q[b], uint32_t(angle), uint32_t(side), uint32_t(b));
        }
    }
    (side == 0 ? ms.f_err : ms.t_err).push_back(std::move(fe));
    (side == 0 ? ms.f : ms.t).push_back(std::move(f));
}

std::vector<ModelSlices> ModelEvaluator::Impl::evaluate(const Stack& s, const ModelGrid& grid,
                                                        std::vector<ModelCost>* costs, const ModelOptions& options,
                                                        ModelStageCost* stage) {
    const auto stage0 = Clock::now();
    ModelStageCost sc;
    renew_pipelines_if_due();
    use_azimuth(grid);
    assign_user_slots(options);
    ensure_grid(size_t(grid.n_theta) * grid.n_phi);
    // plan: what the stack implies for the models, each model's terms, the pipelines
    const ModelStack mstack = model_stack(s, options, table_kernel);
    inputs.upload(mstack);
    sc.setup_seconds = since(stage0);
    const Plans plans = plan_models(mstack, grid, options);
    const auto pipes0 = Clock::now();
    sc.pipelines_created = prepare(plans.need);
    sc.pipeline_seconds = since(pipes0);
    if (costs) costs->clear();
    std::vector<ModelSlices> out;
    bool table_charged = false;   // the tables' device time, shared by the models that read them: the first's
    const int sides = s.transmissive() ? 2 : 1;
    for (size_t m = 0; m < model_registry().size(); ++m) {
        ModelSlices ms;
        ms.id = model_registry()[m].id;
        ms.claims_reciprocal = model_registry()[m].reciprocal;
        ms.claims_energy_conserving = model_registry()[m].energy_conserving;
        ms.energy_note = model_registry()[m].energy_note;
        ms.not_applicable = mstack.skipped[m];
        ms.not_selected = !model_not_selected(m, options).empty();
        ModelCost cost;
        const auto t0 = Clock::now();
        if (ms.not_applicable.empty() && as_black_box(m, options)) {
            ms.integration = "black box";
            integrate_black_box(ms, kernel(MODEL_KERNEL_QUADRATURE, uint32_t(m)), mstack, grid, cost, false);
        } else if (ms.not_applicable.empty()) {
            if (uses_tables(m) && options.belcour_tables && !table_charged) {
                cost.device_seconds += mstack.table_seconds;
                table_charged = true;
            }
            // record -> read back, per incident angle and side
            for (size_t angle = 0, i = 0; angle < grid.theta_i_deg.size(); ++angle)
                for (int side = 0; side < sides; ++side) {
                    const std::vector<TermPlan>& terms = plans.terms[m][i++];
                    double narrowest;
                    const uint32_t quad_terms = quadrature_terms(terms, narrowest);
                    const ModelPush pc = quadrature_push(
                        quad_terms, grid, grid.theta_i_deg[angle], side, mstack, narrowest, !uses_tables(m),
                        quadrature_max_rects(shader_model_of(m), s), options.belcour_tables);
                    ctx.run_now([&](vk::CommandBuffer c) {
                        record_planned(c, uint32_t(m), terms, pc, grid.theta_i_deg[angle], grid);
                    });
                    ++submissions;
                    read_planned(ms, cost, terms, quad_terms != 0, angle, side, grid);
                }
        }
        cost.wall_seconds = since(t0);
        sc.device_seconds += cost.device_seconds;
        ms.invalid = describe_invalid(ms, grid);
        if (costs) costs->push_back(cost);
        out.push_back(std::move(ms));
    }
    for (const auto& um : options.user_models) {
        ModelCost cost;
        const auto t0 = Clock::now();
        ModelSlices ms = evaluate_black_box(*um, mstack, grid, options, cost, sc);
        cost.wall_seconds = since(t0);
        cost.compile_seconds = um->compile_seconds;
        sc.user_compile_seconds += um->compile_seconds;
        sc.device_seconds += cost.device_seconds;
        ms.invalid = describe_invalid(ms, grid);
        if (costs) costs->push_back(cost);
        out.push_back(std::move(ms));
    }
    sc.wall_seconds = since(stage0);
    if (stage) *stage = sc;
    return out;
}

ModelEvaluator::ModelEvaluator(VkContext& ctx) : impl_(new Impl(ctx)) {}
ModelEvaluator::~ModelEvaluator() { delete impl_; }
const std::vector<float>& ModelEvaluator::belcour_tables(const StackGpu& sg) { return impl_->table_kernel.tables(sg); }
double ModelEvaluator::table_seconds() const { return impl_->table_kernel.seconds(); }
std::vector<ModelSlices> ModelEvaluator::evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs,
                                                  const ModelOptions& options, ModelStageCost* stage) {
    return impl_->evaluate(s, grid, costs, options, stage);
}

std::vector<ModelSlices> evaluate_models(VkContext& ctx, const Stack& s, const ModelGrid& grid,
                                         std::vector<ModelCost>* costs, const ModelOptions& options,
                                         ModelStageCost* stage) {
    ModelEvaluator e(ctx);
    return e.evaluate(s, grid, costs, options, stage);
}

}   // namespace gonio
