// reference_batch.cpp: simulate_gpu_batch, the walk runner with shaders/simulate_batch.comp: many stacks per
// dispatch (see reference.h).
#include "angle_policy.h"
#include "reference.h"
#include "compute_kernel.h"
#include "histogram.h"
#include "stack_gpu.h"
#include "vk_context.h"
#include "walk_runner.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "simulate_batch_spv.h"

namespace gonio {

namespace {

// The stacks' walks, checked to share one kernel: the same layers and base kind, and for the specialised walk the same
// specialisation; one staging scale for the whole batch, the largest any stack needs.
std::vector<WalkStack> batch_walks(const std::vector<Stack>& stacks, const SimOptions& opt, WalkSpec& ws) {
    std::vector<WalkStack> walks;
    int weight_shift = 0;
    for (const Stack& s : stacks) {
        validate_stack(s);
        walks.push_back(walk_stack_for(s, opt));
        const WalkSpec &w = walks.back().spec, &w0 = walks.front().spec;
        weight_shift = std::max(weight_shift, walks.back().weight_shift);
        if (w.layer_count != w0.layer_count || w.base_kind != w0.base_kind)
            throw std::invalid_argument(
                "simulate_gpu_batch: the stacks of a batch must have the same layers and base kind");
        if (opt.specialised && !(w == w0))
            throw std::invalid_argument(
                "simulate_gpu_batch: stacks with different rough or absorbing layers, or where the "
                "Lambertian series applies to some but not all, need the general walk");
    }
    for (WalkStack& w : walks) w.set_staging_shift(weight_shift);
    ws = walks.front().spec;
    // the general walk carries the free-flight code where any stack of the batch scatters (walk.glsl)
    if (!opt.specialised)
        for (const WalkStack& w : walks) ws.scatter_mask |= w.spec.scatter_mask;
    return walks;
}

// One incident angle of every stack of the batch: dispatches until each stack has its paths or met its --rse target
// at a checkpoint (AnglePolicy: as simulate_gpu, paths grow in rounds and a stack stops at the first checkpoint where
// its relative standard error meets the target, so each stack gets exactly the paths and bits of its own simulate_gpu
// run; stopped stacks stay in the dispatch but their workgroups return at once).
struct BatchAngle {
    WalkRunner& runner;
    const ComputeKernel& sim;
    const SimOptions& opt;
    std::vector<SimResult>& res;
    BatchStack* live;
    uint32_t shift;
    uint64_t batch;

    void run(size_t a, const WalkGrid& grid) {
        const AnglePolicy policy{opt};
        const size_t C = res.size();
        const WalkDispatch wd(opt.paths_per_invocation);
        runner.clear();
        WalkPush pc =
            walk_push(grid, opt.dtheta_deg, opt.dphi_deg, opt.max_events, opt.theta_i_deg[a], opt.seed, uint32_t(a));
        pc.staging_stride = uint32_t(grid.values() / 2);
        double device_seconds = 0;
        const auto t0 = std::chrono::steady_clock::now();
        for (size_t i = 0; i < C; ++i) live[i].extra.y = 1;
        std::vector<std::string> stopped_by(C, "paths");
        std::vector<AngleResult> finished(C);
        size_t active = C;
        uint64_t done = 0, checkpoint = policy.next_checkpoint(0);
        auto angle_of = [&](size_t i, uint64_t paths) {
            AngleResult ar = runner.angle(i, paths);
            ar.theta_i_deg = opt.theta_i_deg[a];
            return ar;
        };
        while (active > 0 && done < opt.paths) {
            uint64_t n = std::min(batch, checkpoint - done);
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            device_seconds += runner.run(sim, pc, wd.groups(n), uint32_t(C), shift);
            done += n;
            if (opt.rse_target > 0 && done == checkpoint && done < opt.paths) {
                runner.read_back();
                for (size_t i = 0; i < C; ++i) {
                    if (!live[i].extra.y) continue;
                    AngleResult cur = angle_of(i, done);
                    if (policy.rse_met(policy.rse(res[i], cur))) {   // as simulate_gpu: stop here
                        live[i].extra.y = 0;
                        active--;
                        stopped_by[i] = "rse";
                        finished[i] = std::move(cur);
                    }
                }
                checkpoint = policy.next_checkpoint(done);
            }
        }
        runner.read_back();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (size_t i = 0; i < C; ++i) {
            AngleResult ar = live[i].extra.y ? angle_of(i, done) : std::move(finished[i]);
            ar.seconds = seconds / double(C);   // shared: each stack's share of the batch
            ar.device_seconds = device_seconds / double(C);
            summarise_relative_se(res[i], ar);
            // the last checkpoint is the cap: simulate_gpu reports "rse" there if the target is met
            ar.stopped_by = !live[i].extra.y ? stopped_by[i] : policy.rse_met(policy.rse(res[i], ar)) ? "rse" : "paths";
            res[i].angles.push_back(std::move(ar));
        }
    }
};

}   // namespace

std::vector<SimResult> simulate_gpu_batch(VkContext& ctx, const std::vector<Stack>& stacks,
                                          const std::vector<uint32_t>& seeds, const SimOptions& opt) {
    validate_options(opt);
    if (stacks.empty()) return {};
    if (seeds.size() != stacks.size()) throw std::invalid_argument("simulate_gpu_batch: one seed per stack");
    if (opt.max_seconds > 0)
        throw std::invalid_argument("simulate_gpu_batch: no --max-seconds (a batch's stacks share their time)");
    if (stacks.size() > 65535) throw std::invalid_argument("simulate_gpu_batch: at most 65535 stacks per batch");
    WalkSpec ws;
    const std::vector<WalkStack> walks = batch_walks(stacks, opt, ws);
    const size_t C = stacks.size();
    // the same base kind for every stack (checked above), so the same sides
    const WalkGrid grid = walk_grid(opt.dtheta_deg, opt.dphi_deg, opt.orders, stacks[0].transmissive());
    std::vector<SimResult> res;
    for (size_t i = 0; i < C; ++i) {
        SimOptions o = opt;
        o.seed = seeds[i];
        // the batch reads its stacks from a buffer: never baked
        res.push_back(start_result(stacks[i], o, ctx.device_info().name, ctx.driver_string(), grid,
                                   walk_ran(walks[i], o, false)));
    }
    WalkRunner runner(ctx, grid.values(), C, vk::DescriptorType::eStorageBuffer, C * sizeof(BatchStack),
                      std::to_string(C) + " configurations per batch of this grid");
    BatchStack* live = static_cast<BatchStack*>(runner.stack_mapped());
    for (size_t i = 0; i < C; ++i) {
        BatchStack b{};
        b.stack = walks[i].gpu;
        b.extra = uvec4(seeds[i], 1u, 0u, 0u);   // seed, active
        std::memcpy(&live[i], &b, sizeof b);
    }
    std::unique_ptr<ComputeKernel> sim = runner.make_kernel(simulate_batch_spv, sizeof(simulate_batch_spv));
    build_walk_kernel(*sim, ctx.device(), ws, opt.orders, opt.paths_per_invocation);
    const WalkDispatch wd(opt.paths_per_invocation);
    // paths per dispatch, per stack: about 2^20 path-stacks per submission (results do not depend on it)
    const uint64_t batch = std::max<uint64_t>(
        wd.per_group, std::min<uint64_t>(wd.max_paths, ((1ull << 20) / C / wd.per_group + 1) * wd.per_group));
    BatchAngle angle{runner, *sim, opt, res, live, uint32_t(walks.front().staging_shift), batch};
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) angle.run(a, grid);
    return res;
}

}   // namespace gonio
