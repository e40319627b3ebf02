#include "model_evaluator.h"
#include "belcour_tables_host.h"
#include "coat_albedo.h"
#include "compute_kernel.h"
#include "model_applicability.h"
#include "model_plan.h"
#include "model_twin.h"
#include "user_model.h"
#include "models_spv_table.h"   // generated (CMakeLists.txt): models_N_spv.h, one per built-in model file

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <map>
#include <memory>
#include <set>
#include <thread>

namespace gonio {

namespace {

// models.comp, one SPIR-V module per built-in model file (CMakeLists.txt: GONIO_MODEL_ONLY), by code
struct ModelSpv {
    const uint32_t* code;
    size_t bytes;
};
const ModelSpv kModelSpv[] = {GONIO_MODELS_SPV};

// bytes per bin of models.comp's outputs (kernel_interface.glsl)
constexpr size_t kQuadBytes = QUAD_FLOATS_PER_BIN * sizeof(float), kLobeBytes = LOBE_SUMS_PER_BIN * sizeof(int64_t);
// a user's delta lobes as models.comp books them (GONIO_MODEL_HINTS): a count, then (weight, bin) per lobe
constexpr size_t kDeltaBytes = (1 + GONIO_MAX_HINTS) * 4 * sizeof(float);

// Bin b's quadrature outputs q (QUAD_FLOATS_PER_BIN floats, models.comp): nodes where the model's value could not
// be used, and a quadrature the loop limiter cut short, booked on the model.
void note_invalid(ModelSlices& ms, const float* q, uint32_t angle, uint32_t side, uint32_t bin) {
    if (q[7] > 0.0f) {
        ms.invalid_nodes += uint64_t(q[7]);
        ms.invalid_bins.push_back({angle, side, bin});
    }
    if (q[3] < 0.0f) ms.cut_short_bins.push_back({angle, side, bin});
    // the same in every bin of a dispatch (l fixed): once per incident angle and side
    const uint32_t hints = uint32_t(q[8]);
    auto once = [&](std::vector<ModelSlices::BinRef>& v) {
        if (v.empty() || v.back().angle != angle || v.back().side != side) v.push_back({angle, side, 0});
    };
    if (hints & 1u) once(ms.invalid_hints);
    if (hints & 2u) once(ms.float_unresolved);
}

// "theta_i A R; theta_i B T; ..." (the first three)
std::string where_angles(const std::vector<ModelSlices::BinRef>& v, const ModelGrid& grid) {
    std::string at;
    for (size_t i = 0; i < v.size() && i < 3; ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%stheta_i %g %s", i ? "; " : "", grid.theta_i_deg[v[i].angle],
                      v[i].side ? "T" : "R");
        at += buf;
    }
    if (v.size() > 3) at += "; ...";
    return at;
}

// "" where every value can be used, else why not, with where (the first bins).
std::string describe_invalid(const ModelSlices& ms, const ModelGrid& grid) {
    auto where = [&](const std::vector<ModelSlices::BinRef>& bins) {
        std::string w;
        for (size_t i = 0; i < bins.size() && i < 3; ++i) {
            const auto& r = bins[i];
            const uint32_t t = r.bin / grid.n_phi, p = r.bin % grid.n_phi;
            char buf[160];
            std::snprintf(buf, sizeof buf, "%stheta_i %g %s theta %g-%g phi %g", i ? "; " : "",
                          grid.theta_i_deg[r.angle], r.side ? "T" : "R", t * grid.dtheta_deg,
                          std::min(90.0, (t + 1) * grid.dtheta_deg), p * grid.dphi_deg);
            w += buf;
        }
        if (bins.size() > 3) w += "; ...";
        return w;
    };
    std::string why;
    if (ms.invalid_nodes > 0)
        why = std::to_string(ms.invalid_nodes) + " quadrature nodes in " + std::to_string(ms.invalid_bins.size()) +
              " bins where f is NaN, infinite or negative (" + where(ms.invalid_bins) + ")";
    if (!ms.invalid_hints.empty())
        why += (why.empty() ? "" : "; ") +
               std::string(
                   "model_lobes gave an unusable lobe (a NaN or infinite direction, a negative roughness, or "
                   "more than 8 lobes; ") +
               where_angles(ms.invalid_hints, grid) + ")";
    if (!ms.float_unresolved.empty())
        why += (why.empty() ? "" : "; ") +
               std::string(
                   "a black box cannot integrate a lobe narrower in v than float resolves (2 alpha cos theta "
                   "below 2e-5; ") +
               where_angles(ms.float_unresolved, grid) +
               "; its lobes: model_lobes, else the stack's narrowest interface): the built-in models put such lobes "
               "on visible-normal grids";
    if (!ms.cut_short_bins.empty())
        why += (why.empty() ? "" : "; ") + std::to_string(ms.cut_short_bins.size()) +
               " bins whose quadrature lavapipe's loop limiter cut short (its 65535 loop trips per invocation; " +
               where(ms.cut_short_bins) + ")";
    return why;
}

// The projected solid angle of the bins in theta ring t (sr), as the lobe grids' sums are divided by it
double ring_projected_omega(const ModelGrid& grid, uint32_t t) {
    const double lo = t * grid.dtheta_deg * M_PI / 180, hi = (t + 1) * grid.dtheta_deg * M_PI / 180;
    return 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * grid.dphi_deg * M_PI / 180;
}

// The roughness a black-box model's quadrature is graded with towards the mirror direction: the stack's narrowest
// interface (a smooth one as MODEL_MIN_ALPHA, as the built-in models evaluate it); 0: no interface but a
// Lambertian one
double black_box_roughness(const Stack& s) {
    double a = 0.0;
    for (const Layer& L : s.layers) {
        if (L.kind == InterfaceKind::Lambertian) continue;
        const double r = std::max(double(L.roughness), double(MODEL_MIN_ALPHA));
        a = a > 0.0 ? std::min(a, r) : r;
    }
    return a;
}

// The push constants of models.comp's dispatches at incident angle theta (degrees) and side for the quadrature of
// `terms` whose narrowest lobe has roughness `narrowest` (0: none); coat_model: a two-layer model's terms (the
// base terms stop at the critical angle of a coat of lower index).
ModelPush quadrature_push(uint32_t model, uint32_t terms, const ModelGrid& grid, double theta, int side, const Stack& s,
                          double narrowest, bool coat_model, uint32_t max_rects, bool tables) {
    const double ti = theta * M_PI / 180;
    const double eta = s.layers[0].ior.x / s.exterior_ior;
    // v beyond the critical angle of a coat of lower index (a denser exterior) cannot enter it: the base terms of
    // the two-layer models stop there
    return ModelPush{
        model, terms, grid.n_theta, grid.n_phi, float(grid.dtheta_deg * M_PI / 180), float(grid.dphi_deg * M_PI / 180),
        float(std::sin(ti)), float(std::cos(ti)), lobe_grid_nodes(theta), 0.0f, 0u, 0.0f, uint32_t(side),
        tables ? 1u : 0u, 0u, 0.0f, lobe_grid_nodes(theta), float(2.0 * narrowest),
        std::sin(ti) > 1e-6 ? float(narrowest) : 0.0f, float(narrowest),
        coat_model && eta < 1.0 ? float(std::asin(eta)) : 0.0f, max_rects,
        s.layers[0].kind == InterfaceKind::Dielectric && eta < 1.0 ? float(std::sqrt(1.0 - eta * eta)) : 0.0f,
        float(mu_jump_of(s)),
        // the lobe's width in the components of v, 2 alpha cos(theta_i), against 1e-4 (1700 float steps of 6e-8):
        // narrower lobes get up to 8x finer pieces at their peak (models.comp)
        narrowest > 0.0 ? float(std::clamp(1e-4 / (2.0 * narrowest * std::max(std::cos(ti), 1e-3)), 1.0, 8.0)) : 1.0f,
        1u, 0u};
}

}   // namespace

ModelGrid model_grid(const SimResult& r) {
    return {r.n_theta, r.n_phi, r.options.dtheta_deg, r.options.dphi_deg, r.options.theta_i_deg};
}

struct ModelEvaluator::Impl {
    VkContext& ctx;
    Buffer ubo, albedo, tables, lobes;
    Buffer quad, lobe, host;
    size_t nb = 0;   // bins the grid buffers hold
    std::map<std::pair<uint32_t, uint32_t>, std::unique_ptr<ComputeKernel>>
        kernels;   // (kernel, model), built when first used
    std::map<const UserModel*, std::unique_ptr<ComputeKernel>> user_kernels;   // users' models' quadrature kernels
    BelcourTableKernel table_kernel;   // Belcour's tables for the stacks seen (and on disk)
    vk::raii::QueryPool queries = nullptr;

    explicit Impl(VkContext& c) : ctx(c), table_kernel(c) {
        ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
        albedo = ctx.make_buffer(COAT_ALBEDO_NODES * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
        tables = ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, true);
        std::memset(tables.mapped, 0, TABLE_FLOATS * 4);
        lobes = ctx.make_device_buffer(BELCOUR_MU_NODES * BELCOUR_LOBE_STRIDE * sizeof(vec4),
                                       vk::BufferUsageFlagBits::eStorageBuffer);
        queries = vk::raii::QueryPool(ctx.device(),
                                      vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    }

    void ensure_grid(size_t bins) {
        if (bins <= nb) return;
        auto& dev = ctx.device();
        nb = bins;
        quad = ctx.make_device_buffer(nb * kQuadBytes, vk::BufferUsageFlagBits::eStorageBuffer);
        lobe = ctx.make_device_buffer(nb * kLobeBytes, vk::BufferUsageFlagBits::eStorageBuffer);
        host =
            ctx.make_buffer(nb * (kQuadBytes + kLobeBytes) + kDeltaBytes, vk::BufferUsageFlagBits::eTransferDst, false);
        for (auto& [key, k] : kernels) k->bind(dev, buffers());
        for (auto& [um, k] : user_kernels) k->bind(dev, buffers());
    }

    // models.comp's buffers, indexed by binding (MODEL_BINDING_*, kernel_interface.glsl)
    static std::vector<vk::DescriptorType> model_descriptor_types() {
        std::vector<vk::DescriptorType> t(MODEL_BINDINGS, vk::DescriptorType::eStorageBuffer);
        t[MODEL_BINDING_STACK] = vk::DescriptorType::eUniformBuffer;
        return t;
    }
    std::vector<const Buffer*> buffers() const {
        std::vector<const Buffer*> b(MODEL_BINDINGS, nullptr);
        b[MODEL_BINDING_STACK] = &ubo;
        b[MODEL_BINDING_QUADRATURE] = &quad;
        b[MODEL_BINDING_LOBE_SUMS] = &lobe;
        b[MODEL_BINDING_COAT_ALBEDO] = &albedo;
        b[MODEL_BINDING_BELCOUR_TABLES] = &tables;
        b[MODEL_BINDING_BELCOUR_LOBES] = &lobes;
        return b;
    }

    // `model`: a registry index; its pipeline is its base model's module specialised with its conventions
    std::unique_ptr<ComputeKernel> make_kernel(uint32_t which, uint32_t model) {
        const uint32_t code = shader_model_of(model), convention = model_registry().at(model).convention;
        if (code >= std::size(kModelSpv))
            throw std::runtime_error("models.comp: no SPIR-V module for model " + std::to_string(code));
        auto& dev = ctx.device();
        auto k = std::make_unique<ComputeKernel>(dev, kModelSpv[code].code, kModelSpv[code].bytes,
                                                 model_descriptor_types(), uint32_t(sizeof(ModelPush)));
        uint32_t spec[3] = {which, code, convention};
        k->build(dev, {{MODEL_SPEC_KERNEL, 0, 4}, {MODEL_SPEC_MODEL, 4, 4}, {MODEL_SPEC_CONVENTION, 8, 4}}, spec,
                 sizeof spec);
        k->bind(dev, buffers());
        return k;
    }

    ComputeKernel& kernel(uint32_t which, uint32_t model) {
        auto& k = kernels[{which, model}];
        if (!k) k = make_kernel(which, model);
        return *k;
    }

    // Creates the pipelines in `need` that do not exist yet, concurrently (vkCreateComputePipelines is where
    // lavapipe translates and optimises the shader, on the calling thread; each pipeline has its own module,
    // layout and descriptor pool, so no object is shared between the threads). Returns how many it made.
    uint32_t prepare(const std::set<std::pair<uint32_t, uint32_t>>& need) {
        std::vector<std::pair<uint32_t, uint32_t>> todo;
        for (auto& key : need)
            if (!kernels.count(key) || !kernels[key]) todo.push_back(key);
        std::vector<std::unique_ptr<ComputeKernel>> made(todo.size());
        std::atomic<size_t> next{0};
        auto work = [&] {
            for (size_t i; (i = next++) < todo.size();) made[i] = make_kernel(todo[i].first, todo[i].second);
        };
        const unsigned threads =
            std::min<unsigned>(std::max(1u, std::thread::hardware_concurrency()), unsigned(todo.size()));
        std::vector<std::future<void>> pool;
        for (unsigned t = 1; t < threads; ++t) pool.push_back(std::async(std::launch::async, work));
        work();
        for (auto& f : pool) f.get();   // rethrows a worker's exception
        for (size_t i = 0; i < todo.size(); ++i) kernels[todo[i]] = std::move(made[i]);
        return uint32_t(todo.size());
    }

    std::vector<ModelSlices> evaluate(const Stack& s, const ModelGrid& grid, std::vector<ModelCost>* costs,
                                      const ModelOptions& options, ModelStageCost* stage);

    // ---- a user's model, integrated as a black box (docs/MODELS.md "Your own model") ----
    std::unique_ptr<ComputeKernel> make_user_kernel(const UserModel& um) {
        auto& dev = ctx.device();
        auto k = std::make_unique<ComputeKernel>(dev, um.spirv.data(), um.spirv.size() * sizeof(uint32_t),
                                                 model_descriptor_types(), uint32_t(sizeof(ModelPush)));
        uint32_t spec[3] = {MODEL_KERNEL_QUADRATURE, 1000u, 0u};
        k->build(dev, {{MODEL_SPEC_KERNEL, 0, 4}, {MODEL_SPEC_MODEL, 4, 4}, {MODEL_SPEC_CONVENTION, 8, 4}}, spec,
                 sizeof spec);
        k->bind(dev, buffers());
        return k;
    }
    // One quadrature dispatch (every bin, or the 64-bin blocks listed) and its outputs per bin.
    struct QuadOut {
        std::vector<glm::dvec3> f, err;
        std::vector<float> raw;   // QUAD_FLOATS_PER_BIN per bin, as models.comp wrote them
        std::vector<glm::vec4> deltas;   // with_deltas: a user's delta lobes on this side, (weight, bin)
    };
    QuadOut run_quadrature(ComputeKernel& k, ModelPush pc, size_t nb, const std::vector<uint32_t>* blocks,
                           ModelCost& cost, bool with_deltas = false) {
        ctx.run_now([&](vk::CommandBuffer c) {
            c.resetQueryPool(*queries, 0, 2);
            c.fillBuffer(*quad.buffer, 0, VK_WHOLE_SIZE, 0);
            vk::MemoryBarrier fill{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eShaderWrite};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, fill,
                              nullptr, nullptr);
            c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
            c.bindPipeline(vk::PipelineBindPoint::eCompute, *k.pipeline);
            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *k.layout, 0, {*k.set}, nullptr);
            if (!blocks) {
                c.pushConstants<ModelPush>(*k.layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                c.dispatch(uint32_t((nb + MODEL_GROUP_SIZE - 1) / MODEL_GROUP_SIZE), 1, 1);
            } else {
                for (uint32_t g : *blocks) {   // each block writes its own bins: no barrier between them
                    pc.bin_first = g * MODEL_GROUP_SIZE;
                    c.pushConstants<ModelPush>(*k.layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                    c.dispatch(1, 1, 1);
                }
            }
            c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
            vk::MemoryBarrier done{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eTransferRead};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, done,
                              nullptr, nullptr);
            c.copyBuffer(*quad.buffer, *host.buffer, vk::BufferCopy{0, 0, nb * kQuadBytes});
            if (with_deltas) c.copyBuffer(*lobes.buffer, *host.buffer, vk::BufferCopy{0, nb * kQuadBytes, kDeltaBytes});
            vk::MemoryBarrier read{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eHostRead};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, read, nullptr,
                              nullptr);
        });
        auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                     vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
        cost.device_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
        QuadOut o;
        const float* q = static_cast<const float*>(host.mapped);
        o.raw.assign(q, q + nb * QUAD_FLOATS_PER_BIN);
        if (with_deltas) {
            const auto* d = reinterpret_cast<const glm::vec4*>(q + nb * QUAD_FLOATS_PER_BIN);
            const size_t n = std::min<size_t>(size_t(std::max(0.0f, d[0].x)), GONIO_MAX_HINTS);
            o.deltas.assign(d + 1, d + 1 + n);
        }
        o.f.resize(nb);
        o.err.resize(nb);
        for (size_t b = 0; b < nb; ++b) {
            for (int c = 0; c < 3; ++c) {
                o.f[b][c] = double(q[b * QUAD_FLOATS_PER_BIN + c]);
                o.err[b][c] = double(q[b * QUAD_FLOATS_PER_BIN + 4 + c]);
            }
            cost.evaluations += uint64_t(std::max(0.0f, q[b * QUAD_FLOATS_PER_BIN + 3]));
        }
        return o;
    }
    ModelSlices evaluate_black_box(const UserModel& um, const Stack& s, const ModelGrid& grid,
                                   const ModelOptions& options, ModelCost& cost, ModelStageCost& sc);
    // The black box's quadrature (below) into ms with kernel k (a user's model: push model 1000; a built-in model
    // with no plan: its registry index).
    // hints: the model announces its lobes (model_lobes), which the device checks instead of the stack's roughness
    void integrate_black_box(ModelSlices& ms, ComputeKernel& k, uint32_t push_model, const Stack& s,
                             const ModelGrid& grid, ModelCost& cost, bool hints);
};

ModelEvaluator::ModelEvaluator(VkContext& ctx) : impl_(new Impl(ctx)) {}
ModelEvaluator::~ModelEvaluator() { delete impl_; }
const std::vector<float>& ModelEvaluator::belcour_tables(const Stack& s) { return impl_->table_kernel.tables(s); }
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

std::vector<ModelSlices> ModelEvaluator::Impl::evaluate(const Stack& s, const ModelGrid& grid,
                                                        std::vector<ModelCost>* costs, const ModelOptions& options,
                                                        ModelStageCost* stage) {
    using clock = std::chrono::steady_clock;
    const auto stage0 = clock::now();
    auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
    ModelStageCost sc;
    const size_t nb = size_t(grid.n_theta) * grid.n_phi;
    ensure_grid(nb);
    StackGpu sg = pack_stack(s);
    sg.info.z = s.exterior_ior;   // for a user's model (models/user_model.glsl gonio_exterior_ior); the walk's
        // StackGpu leaves it 0
    std::memcpy(ubo.mapped, &sg, sizeof(sg));
    std::vector<float> table(COAT_ALBEDO_NODES, 0.0f);
    if (s.layers.size() == 2 && !s.transmissive()) table = coat_albedo_table(s);
    std::memcpy(albedo.mapped, table.data(), COAT_ALBEDO_NODES * 4);
    std::vector<ModelSlices> out;
    if (costs) costs->clear();
    // why model m does not run here: it cannot represent the stack, or it is not among the selected (--models)
    auto skipped = [&](size_t m) {
        std::string why = model_not_selected(m, options);
        return why.empty() ? model_cannot_represent(m, s) : why;
    };
    bool need_tables = false;
    for (size_t m = 0; m < model_registry().size(); ++m)
        need_tables |= uses_tables(m) && options.belcour_tables && skipped(m).empty();
    double table_before = table_kernel.seconds();
    std::vector<float> tables_now;   // what the device reads (planning looks at the lobes they give)
    if (need_tables) {
        const std::vector<float>& t = table_kernel.tables(s);
        std::memcpy(tables.mapped, t.data(), TABLE_FLOATS * 4);
        tables_now = t;
    }
    const double table_cost =
        table_kernel.seconds() - table_before;   // shared by Belcour's models: charged to the first
    bool table_charged = false;
    sc.setup_seconds = since(stage0);
    // every model's plan at every angle and side, then the pipelines they need (only those), made concurrently
    const int sides = s.transmissive() ? 2 : 1;
    std::vector<std::vector<std::vector<TermPlan>>> plans(model_registry().size());
    std::set<std::pair<uint32_t, uint32_t>> need;
    // a built-in model with no plan (model_plan.h PlanKind::BlackBox) is integrated as a black box, as a user's
    auto black_box = [&](size_t m) {
        return plan_kind(shader_model_of(m)) == PlanKind::BlackBox ||
               std::find(options.as_black_box.begin(), options.as_black_box.end(), model_registry()[m].id) !=
                   options.as_black_box.end();
    };
    for (size_t m = 0; m < model_registry().size(); ++m) {
        if (!skipped(m).empty()) continue;
        if (black_box(m)) {
            need.insert({MODEL_KERNEL_QUADRATURE, uint32_t(m)});
            continue;
        }
        if (uses_tables(m)) need.insert({MODEL_KERNEL_LOBES, uint32_t(m)});
        for (double theta : grid.theta_i_deg)
            for (int side = 0; side < sides; ++side) {
                plans[m].push_back(plan(shader_model_of(m), s, theta, side,
                                        uses_tables(m) && options.belcour_tables ? &tables_now : nullptr,
                                        model_registry()[m].convention));
                for (auto& t : plans[m].back())
                    need.insert({t.alpha_grid == 0 ? MODEL_KERNEL_QUADRATURE : MODEL_KERNEL_LOBE_GRID, uint32_t(m)});
            }
    }
    const auto pipes0 = clock::now();
    sc.pipelines_created = prepare(need);
    sc.pipeline_seconds = since(pipes0);
    for (size_t m = 0; m < model_registry().size(); ++m) {
        ModelSlices ms;
        ms.id = model_registry()[m].id;
        ms.not_applicable = skipped(m);
        ModelCost cost;
        auto t0 = std::chrono::steady_clock::now();
        if (ms.not_applicable.empty() && black_box(m)) {
            ms.integration = "black box";
            integrate_black_box(ms, kernel(MODEL_KERNEL_QUADRATURE, uint32_t(m)), uint32_t(m), s, grid, cost, false);
        } else if (ms.not_applicable.empty()) {
            if (uses_tables(m) && options.belcour_tables && !table_charged) {
                cost.device_seconds += table_cost;
                table_charged = true;
            }
            size_t plan_index = 0;
            for (size_t angle = 0; angle < grid.theta_i_deg.size(); ++angle) {
                const double theta = grid.theta_i_deg[angle];
                for (int side = 0; side < sides; ++side) {
                    const std::vector<TermPlan>& terms = plans[m][plan_index++];
                    uint32_t quad_terms = 0;
                    double narrowest = 0.0;   // the narrowest lobe among the quadrature's terms (0: none)
                    for (auto& t : terms)
                        if (t.alpha_grid == 0) {
                            quad_terms |= t.term;
                            if (t.alpha_eff > 0.0)
                                narrowest = narrowest > 0.0 ? std::min(narrowest, t.alpha_eff) : t.alpha_eff;
                        }
                    ModelPush pc =
                        quadrature_push(uint32_t(m), quad_terms, grid, theta, side, s, narrowest, !uses_tables(m),
                                        quadrature_max_rects(shader_model_of(m), s), options.belcour_tables);
                    bool any_grid = false;
                    for (auto& t : terms) any_grid |= t.alpha_grid != 0;
                    ComputeKernel* kq = quad_terms ? &kernel(MODEL_KERNEL_QUADRATURE, uint32_t(m)) : nullptr;
                    ComputeKernel* kl = any_grid ? &kernel(MODEL_KERNEL_LOBE_GRID, uint32_t(m)) : nullptr;
                    const bool prepass = uses_tables(m);
                    ComputeKernel* kp = prepass ? &kernel(MODEL_KERNEL_LOBES, uint32_t(m)) : nullptr;
                    ctx.run_now([&](vk::CommandBuffer c) {
                        c.resetQueryPool(*queries, 0, 2);
                        c.fillBuffer(*quad.buffer, 0, VK_WHOLE_SIZE, 0);
                        c.fillBuffer(*lobe.buffer, 0, VK_WHOLE_SIZE, 0);
                        vk::MemoryBarrier fill{
                            .srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                            .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                                          vk::PipelineStageFlagBits::eComputeShader, {}, fill, nullptr, nullptr);
                        c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
                        if (kp) {   // Belcour's lobes for this angle, once (models.comp KERNEL 2)
                            c.bindPipeline(vk::PipelineBindPoint::eCompute, *kp->pipeline);
                            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kp->layout, 0, {*kp->set}, nullptr);
                            c.pushConstants<ModelPush>(*kp->layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                            c.dispatch(plan_kind(shader_model_of(m)) == PlanKind::BelcourSymmetric
                                           ? (BELCOUR_MU_NODES + MODEL_GROUP_SIZE - 1) / MODEL_GROUP_SIZE
                                           : 1,
                                       1, 1);
                            vk::MemoryBarrier lobes_done{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                                         .dstAccessMask = vk::AccessFlagBits::eShaderRead};
                            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                                              vk::PipelineStageFlagBits::eComputeShader, {}, lobes_done, nullptr,
                                              nullptr);
                        }
                        if (quad_terms) {
                            c.bindPipeline(vk::PipelineBindPoint::eCompute, *kq->pipeline);
                            c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kq->layout, 0, {*kq->set}, nullptr);
                            c.pushConstants<ModelPush>(*kq->layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                            c.dispatch(uint32_t((nb + MODEL_GROUP_SIZE - 1) / MODEL_GROUP_SIZE), 1, 1);
                        }
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
                                c.bindPipeline(vk::PipelineBindPoint::eCompute, *kl->pipeline);
                                c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *kl->layout, 0, {*kl->set},
                                                     nullptr);
                                c.pushConstants<ModelPush>(*kl->layout, vk::ShaderStageFlagBits::eCompute, 0, lp);
                                const uint32_t per_group = LOBE_GRID_NODES_PER_INVOCATION * MODEL_GROUP_SIZE;
                                c.dispatch((lp.grid * lp.grid_rows + per_group - 1) / per_group, 1, 1);
                                vk::MemoryBarrier acc{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                                      .dstAccessMask = vk::AccessFlagBits::eShaderRead |
                                                                       vk::AccessFlagBits::eShaderWrite};
                                c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                                                  vk::PipelineStageFlagBits::eComputeShader, {}, acc, nullptr, nullptr);
                            }
                        }
                        c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
                        vk::MemoryBarrier done{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                               .dstAccessMask = vk::AccessFlagBits::eTransferRead};
                        c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                                          vk::PipelineStageFlagBits::eTransfer, {}, done, nullptr, nullptr);
                        c.copyBuffer(*quad.buffer, *host.buffer, vk::BufferCopy{0, 0, nb * kQuadBytes});
                        c.copyBuffer(*lobe.buffer, *host.buffer, vk::BufferCopy{0, nb * kQuadBytes, nb * kLobeBytes});
                        vk::MemoryBarrier read{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                               .dstAccessMask = vk::AccessFlagBits::eHostRead};
                        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {},
                                          read, nullptr, nullptr);
                    });
                    auto [qr, ts] =
                        queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                     vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
                    cost.device_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
                    for (auto& t : terms)
                        if (t.alpha_grid != 0) {
                            const GridShape gs = lobe_grids(theta, grid.n_phi);
                            cost.evaluations +=
                                uint64_t(gs.cols) * gs.rows + (t.delta ? 0 : uint64_t(gs.wide_cols) * gs.wide_rows);
                        }
                    // per bin: the quadrature's RGB bin average, its node count, its error estimate (models.comp)
                    const float* q = static_cast<const float*>(host.mapped);
                    const int64_t* lb =
                        reinterpret_cast<const int64_t*>(static_cast<const char*>(host.mapped) + nb * kQuadBytes);
                    std::vector<glm::dvec3> f(nb), fe(nb);
                    for (size_t b = 0; b < nb; ++b) {
                        const double omega = ring_projected_omega(grid, uint32_t(b / grid.n_phi));
                        for (int c = 0; c < 3; ++c) {
                            f[b][c] = double(q[b * QUAD_FLOATS_PER_BIN + c]) +
                                      double(lb[b * LOBE_SUMS_PER_BIN + c]) / double(LOBE_SCALE) / omega;
                            fe[b][c] = double(q[b * QUAD_FLOATS_PER_BIN + 4 + c]);
                        }
                        if (quad_terms) {
                            cost.evaluations += uint64_t(std::max(0.0f, q[b * QUAD_FLOATS_PER_BIN + 3]));
                            note_invalid(ms, q + b * QUAD_FLOATS_PER_BIN, uint32_t(angle), uint32_t(side), uint32_t(b));
                        }
                    }
                    (side == 0 ? ms.f_err : ms.t_err).push_back(std::move(fe));
                    (side == 0 ? ms.f : ms.t).push_back(std::move(f));
                }
            }
        }
        cost.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        sc.device_seconds += cost.device_seconds;
        ms.invalid = describe_invalid(ms, grid);
        if (costs) costs->push_back(cost);
        out.push_back(std::move(ms));
    }
    for (const auto& um : options.user_models) {
        ModelCost cost;
        const auto t0 = clock::now();
        ModelSlices ms = evaluate_black_box(*um, s, grid, options, cost, sc);
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

// A model as a black box (a user's; integrate_black_box also a built-in model with no plan, model_plan.h): one
// term, the graded quadrature towards the mirror direction at the stack's narrowest roughness (pieces of the whole
// bin elsewhere), then every bin again on pieces of at most 1/4 of its side, then bins where the two disagree, or
// whose 4 x 4 and 3 x 3 rules do, on pieces of 1/16 (so that a narrow lobe the model did not announce, away from
// the mirror direction, is found). A bin's error estimate is the larger of its last rules' difference and its
// change from the level before.
ModelSlices ModelEvaluator::Impl::evaluate_black_box(const UserModel& um, const Stack& s, const ModelGrid& grid,
                                                     const ModelOptions& options, ModelCost& cost, ModelStageCost& sc) {
    using clock = std::chrono::steady_clock;
    ModelSlices ms;
    ms.id = um.header.id;
    ms.integration = um.header.has_lobe_hints ? "black box with lobe hints" : "black box";
    ms.file = um.header.path;
    ms.not_applicable = model_id_not_selected(ms.id, options);
    if (ms.not_applicable.empty()) ms.not_applicable = model_file_cannot_represent(um.header, s);
    if (!ms.not_applicable.empty()) return ms;
    const auto p0 = clock::now();
    auto& kp = user_kernels[&um];
    if (!kp) {
        kp = make_user_kernel(um);
        ++sc.pipelines_created;
    }
    sc.pipeline_seconds += std::chrono::duration<double>(clock::now() - p0).count();
    integrate_black_box(ms, *kp, 1000u, s, grid, cost, um.header.has_lobe_hints);
    return ms;
}

void ModelEvaluator::Impl::integrate_black_box(ModelSlices& ms, ComputeKernel& k, uint32_t push_model, const Stack& s,
                                               const ModelGrid& grid, ModelCost& cost, bool hints) {
    ComputeKernel* kp = &k;
    const size_t nb = size_t(grid.n_theta) * grid.n_phi;
    const double narrowest = black_box_roughness(s);
    const int sides = s.transmissive() ? 2 : 1;
    // the model may loop over the layers in each evaluation, as Belcour's do (the lavapipe budget)
    const uint32_t max_rects0 = quadrature_max_rects_black_box(s);
    for (size_t angle = 0; angle < grid.theta_i_deg.size(); ++angle)
        for (int side = 0; side < sides; ++side) {
            // with no lobe hints, the stack's narrowest interface stands for the model's narrowest lobe, at the mirror
            // (or straight-through) direction (the hints are checked on the device, models.comp)
            if (!hints && narrowest > 0.0 &&
                2.0 * narrowest * std::cos(grid.theta_i_deg[angle] * M_PI / 180) < kFloatUnresolved)
                ms.float_unresolved.push_back({uint32_t(angle), uint32_t(side), 0});
            ModelPush pc = quadrature_push(push_model, TERM_TOP | TERM_BASE, grid, grid.theta_i_deg[angle], side, s,
                                           narrowest, true, max_rects0, false);
            if (hints) {
                // the model's hints are its narrow lobes (models.comp grades towards them): no assumed lobe at the
                // mirror direction, whose atan map costs a smooth bin nearby up to 4.5e-6 in float (docs/MODELS.md);
                // the horizon keeps the stack's narrowest masking fall
                pc.w_theta = 0.0f;
                pc.a_phi = 0.0f;
                pc.refine = 1.0f;
            }
            // level 1; where the loop limiter cut it short, the model's own loops are longer than assumed: fewer
            // pieces per bin, down to one
            QuadOut prev = run_quadrature(*kp, pc, nb, nullptr, cost, hints);
            auto cut = [&](const QuadOut& q) {
                for (size_t b = 0; b < nb; ++b)
                    if (q.raw[b * QUAD_FLOATS_PER_BIN + 3] < 0.0f) return true;
                return false;
            };
            while (cut(prev) && pc.max_rects > 1) {
                pc.max_rects = std::max(1u, pc.max_rects / 4);
                prev = run_quadrature(*kp, pc, nb, nullptr, cost, hints);
            }
            const std::vector<glm::vec4> deltas = prev.deltas;
            for (size_t b = 0; b < nb; ++b)
                note_invalid(ms, &prev.raw[b * QUAD_FLOATS_PER_BIN], uint32_t(angle), uint32_t(side), uint32_t(b));
            // the slice's mean value: the scale of the absolute tolerance
            glm::dvec3 mean(0.0);
            for (auto& v : prev.f) mean += v / double(nb);
            QuadOut fin = prev;
            std::vector<glm::dvec3> err = prev.err;
            std::vector<bool> todo(nb, true);
            for (uint32_t split : {4u, 16u}) {
                if (split * split * 2 > pc.max_rects) break;
                std::vector<uint32_t> blocks;
                for (size_t g = 0; g * MODEL_GROUP_SIZE < nb; ++g) {
                    bool any = false;
                    for (size_t b = g * MODEL_GROUP_SIZE; b < std::min(nb, (g + 1) * MODEL_GROUP_SIZE); ++b)
                        any = any || todo[b];
                    if (any) blocks.push_back(uint32_t(g));
                }
                if (blocks.empty()) break;
                ModelPush pr = pc;
                pr.split = split;
                QuadOut q = run_quadrature(*kp, pr, nb, split == 4u ? nullptr : &blocks, cost);
                for (size_t b = 0; b < nb; ++b) {
                    if (!todo[b]) continue;
                    if (q.raw[b * QUAD_FLOATS_PER_BIN + 3] < 0.0f) {
                        // the model's own loops make these pieces too many for lavapipe's loop limiter: the bin
                        // keeps the level before, with its error estimate
                        todo[b] = false;
                        ++ms.unrefined_bins;
                        continue;
                    }
                    note_invalid(ms, &q.raw[b * QUAD_FLOATS_PER_BIN], uint32_t(angle), uint32_t(side), uint32_t(b));
                    bool again = false;
                    for (int c = 0; c < 3; ++c) {
                        const double tol = 1e-3 * std::fabs(q.f[b][c]) + 1e-4 * std::fabs(mean[c]);
                        const double change = std::fabs(q.f[b][c] - fin.f[b][c]);
                        err[b][c] = std::max(q.err[b][c], change);
                        again = again || q.err[b][c] > tol || change > tol;
                    }
                    fin.f[b] = q.f[b];
                    if (split == 16u) ++ms.refined_bins;
                    todo[b] = again;
                }
            }
            // the announced delta lobes (not in f): each weight whole in the bin of its direction, as a bin average
            // (the weight over the bin's projected solid angle), as the built-in models book theirs
            for (const glm::vec4& d : deltas) {
                const uint32_t b = uint32_t(d.w);   // bin_index's: below nb
                fin.f[b] += glm::dvec3(glm::vec3(d)) / ring_projected_omega(grid, b / grid.n_phi);
            }
            (side == 0 ? ms.f_err : ms.t_err).push_back(std::move(err));
            (side == 0 ? ms.f : ms.t).push_back(std::move(fin.f));
        }
}

}   // namespace gonio
