// model_black_box.cpp: a model integrated as a black box, a user's (docs/MODELS.md "Your own model") or a built-in
// model file with no plan: its pipeline, the quadrature's dispatch and its levels of refinement.
#include "model_evaluator_impl.h"
#include "model_twin.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace gonio {

namespace {

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

}   // namespace

std::unique_ptr<ComputeKernel> ModelEvaluator::Impl::make_user_kernel(const UserModel& um, uint32_t which) {
    auto& dev = ctx.device();
    auto k = std::make_unique<ComputeKernel>(dev, um.spirv.data(), um.spirv.size() * sizeof(uint32_t),
                                             model_descriptor_types(), uint32_t(sizeof(ModelPush)));
    // a user's module holds one model, no conventions; MODEL is its slot of parameters
    const uint32_t spec[4] = {which, user_slots.at(&um), 0u, azimuth ? 1u : 0u};
    k->build(dev, model_spec_entries(), spec, sizeof spec);
    k->bind(dev, buffers());
    return k;
}

ModelAsymmetry ModelEvaluator::Impl::measure_reciprocity(const UserModel& um, ModelCost& cost) {
    const std::vector<glm::vec3> dirs = reciprocity_directions();
    const size_t bytes = dirs.size() * sizeof(glm::vec4);
    if (points.size != bytes) {   // the pairs never change: written once, bound in place of the lobes
        points = ctx.make_buffer(bytes, vk::BufferUsageFlagBits::eStorageBuffer, false);
        for (auto& [m, k] : user_point_kernels) k.reset();
    }
    auto& k = user_point_kernels[&um];
    if (!k) {
        k = make_user_kernel(um, MODEL_KERNEL_POINTS);
        k->bind(ctx.device(), point_buffers());
    }
    auto* p = static_cast<glm::vec4*>(points.mapped);
    for (size_t i = 0; i < dirs.size(); ++i) p[i] = glm::vec4(dirs[i], 0.0f);
    ++submissions;
    ctx.run_now([&](vk::CommandBuffer c) {
        c.resetQueryPool(*queries, 0, 2);
        c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
        k->record(c, ModelPush{}, groups_for(dirs.size() / 2, MODEL_GROUP_SIZE));
        c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
        barrier_compute_to_host(c);
    });
    cost.device_seconds += device_seconds();
    cost.evaluations += dirs.size() / 2;
    std::vector<glm::dvec3> f(dirs.size() / 2);
    for (size_t i = 0; i < f.size(); ++i) f[i] = glm::dvec3(glm::vec3(p[2 * i + 1]));
    return measure_asymmetry(f);
}

ModelEvaluator::Impl::QuadOut ModelEvaluator::Impl::run_quadrature(ComputeKernel& k, ModelPush pc, size_t nb,
                                                                   const std::vector<uint32_t>* blocks, ModelCost& cost,
                                                                   bool with_deltas) {
    const size_t quad_bytes = nb * sizeof(QuadBin);
    ++submissions;
    ctx.run_now([&](vk::CommandBuffer c) {
        c.resetQueryPool(*queries, 0, 2);
        c.fillBuffer(*quad.buffer, 0, VK_WHOLE_SIZE, 0);
        barrier_transfer_to_compute(c);
        c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
        if (!blocks) {
            k.record(c, pc, groups_for(nb, MODEL_GROUP_SIZE));
        } else {
            for (uint32_t g : *blocks) {   // each block writes its own bins: no barrier between them
                pc.bin_first = g * MODEL_GROUP_SIZE;
                k.record(c, pc, 1);
            }
        }
        c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
        barrier_compute_to_transfer(c);
        c.copyBuffer(*quad.buffer, *host.buffer, vk::BufferCopy{0, 0, quad_bytes});
        if (with_deltas) c.copyBuffer(*lobes.buffer, *host.buffer, vk::BufferCopy{0, quad_bytes, kDeltaBytes});
        barrier_transfer_to_host(c);
    });
    cost.device_seconds += device_seconds();
    QuadOut o;
    const auto* q = static_cast<const QuadBin*>(host.mapped);
    o.raw.assign(q, q + nb);
    if (with_deltas) {
        const auto* d = reinterpret_cast<const glm::vec4*>(static_cast<const char*>(host.mapped) + quad_bytes);
        const size_t n = std::min<size_t>(size_t(std::max(0.0f, d[0].x)), GONIO_MAX_HINTS);
        o.deltas.assign(d + 1, d + 1 + n);
    }
    o.f.resize(nb);
    o.err.resize(nb);
    for (size_t b = 0; b < nb; ++b) {
        for (int c = 0; c < kChannels; ++c) {
            o.f[b][c] = double(q[b].f[c]);
            o.err[b][c] = double(q[b].err[c]);
        }
        cost.evaluations += uint64_t(std::max(0.0f, q[b].nodes));
    }
    return o;
}

// A model as a black box (a user's; integrate_black_box also a built-in model with no plan, model_plan.h): one
// term, the graded quadrature towards the mirror direction at the stack's narrowest roughness (pieces of the whole
// bin elsewhere), then every bin again on pieces of at most 1/4 of its side, then bins where the two disagree, or
// whose 4 x 4 and 3 x 3 rules do, on pieces of 1/16 (so that a narrow lobe the model did not announce, away from
// the mirror direction, is found). A bin's error estimate is the larger of its last rules' difference and its
// change from the level before.
ModelSlices ModelEvaluator::Impl::evaluate_black_box(const UserModel& um, const ModelStack& mstack,
                                                     const ModelGrid& grid, const ModelOptions& options,
                                                     ModelCost& cost, ModelStageCost& sc) {
    using clock = std::chrono::steady_clock;
    ModelSlices ms;
    ms.id = um.header.id;
    ms.integration = um.header.has_lobe_hints ? "black box with lobe hints" : "black box";
    ms.file = um.header.path;
    if (um.header.states_reciprocity) ms.claims_reciprocal = um.header.reciprocal;
    if (um.header.states_energy) ms.claims_energy_conserving = um.header.energy_conserving;
    ms.energy_note = um.header.energy_note;
    ms.not_applicable = model_id_not_selected(ms.id, options);
    ms.not_selected = !ms.not_applicable.empty();
    if (ms.not_applicable.empty()) ms.not_applicable = model_file_cannot_represent(um.header, mstack.stack);
    if (!ms.not_applicable.empty()) return ms;
    const auto p0 = clock::now();
    auto& kp = user_kernels[&um];
    if (!kp) {
        kp = make_user_kernel(um);
        ++sc.pipelines_created;
    }
    sc.pipeline_seconds += std::chrono::duration<double>(clock::now() - p0).count();
    integrate_black_box(ms, *kp, mstack, grid, cost, um.header.has_lobe_hints);
    ms.reciprocity = measure_reciprocity(um, cost);
    return ms;
}

void ModelEvaluator::Impl::integrate_black_box(ModelSlices& ms, ComputeKernel& k, const ModelStack& mstack,
                                               const ModelGrid& grid, ModelCost& cost, bool hints) {
    const Stack& s = mstack.stack;
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
            ModelPush pc = quadrature_push(TERM_ALL, grid, grid.theta_i_deg[angle], side, mstack, narrowest, true,
                                           max_rects0, false);
            if (hints) {
                // the model's hints are its narrow lobes (models.comp grades towards them): no assumed lobe at the
                // mirror direction, whose atan map costs a smooth bin nearby up to 4.5e-6 in float (docs/MODELS.md);
                // the horizon keeps the stack's narrowest masking fall
                pc.w_theta = 0.0f;
                pc.a_phi = 0.0f;
                pc.refine = 1.0f;
            }
            integrate_black_box_at(ms, k, pc, angle, side, grid, cost, hints);
        }
}

// Level 1, then every bin again on pieces of at most 1/4 of its side, then bins where the two disagree, or whose
// 4 x 4 and 3 x 3 rules do, on pieces of 1/16.
void ModelEvaluator::Impl::integrate_black_box_at(ModelSlices& ms, ComputeKernel& k, ModelPush pc, size_t angle,
                                                  int side, const ModelGrid& grid, ModelCost& cost, bool hints) {
    const size_t nb = size_t(grid.n_theta) * grid.n_phi;
    // level 1; where the loop limiter cut it short, the model's own loops are longer than assumed: fewer pieces per
    // bin, down to one
    QuadOut prev = run_quadrature(k, pc, nb, nullptr, cost, hints);
    auto cut = [&](const QuadOut& q) {
        return std::any_of(q.raw.begin(), q.raw.end(), [](const QuadBin& b) { return b.nodes < 0.0f; });
    };
    while (cut(prev) && pc.max_rects > 1) {
        pc.max_rects = std::max(1u, pc.max_rects / 4);
        prev = run_quadrature(k, pc, nb, nullptr, cost, hints);
    }
    const std::vector<glm::vec4> deltas = prev.deltas;
    for (size_t b = 0; b < nb; ++b) note_invalid(ms, prev.raw[b], uint32_t(angle), uint32_t(side), uint32_t(b));
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
        QuadOut q = run_quadrature(k, pr, nb, split == 4u ? nullptr : &blocks, cost);
        for (size_t b = 0; b < nb; ++b) {
            if (!todo[b]) continue;
            if (q.raw[b].nodes < 0.0f) {
                // the model's own loops make these pieces too many for lavapipe's loop limiter: the bin keeps the
                // level before, with its error estimate
                todo[b] = false;
                ++ms.unrefined_bins;
                continue;
            }
            note_invalid(ms, q.raw[b], uint32_t(angle), uint32_t(side), uint32_t(b));
            bool again = false;
            for (int c = 0; c < kChannels; ++c) {
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
    // the announced delta lobes (not in f): each weight whole in the bin of its direction, as a bin average (the
    // weight over the bin's projected solid angle), as the built-in models book theirs
    for (const glm::vec4& d : deltas) {
        const uint32_t b = uint32_t(d.w);   // bin_index's: below nb
        fin.f[b] += glm::dvec3(glm::vec3(d)) / ring_projected_omega(grid, b / grid.n_phi);
    }
    (side == 0 ? ms.f_err : ms.t_err).push_back(std::move(err));
    (side == 0 ? ms.f : ms.t).push_back(std::move(fin.f));
}

}   // namespace gonio
