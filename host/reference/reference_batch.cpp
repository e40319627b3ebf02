// reference_batch.cpp: simulate_gpu_batch, the walk runner with shaders/simulate_batch.comp: many stacks per
// dispatch (see reference.h).
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

bool same_spec(const WalkSpec& a, const WalkSpec& b) { return a == b; }

}   // namespace

std::vector<SimResult> simulate_gpu_batch(VkContext& ctx, const std::vector<Stack>& stacks,
                                          const std::vector<uint32_t>& seeds, const SimOptions& opt) {
    validate_options(opt);
    if (stacks.empty()) return {};
    if (seeds.size() != stacks.size()) throw std::invalid_argument("simulate_gpu_batch: one seed per stack");
    if (opt.max_seconds > 0)
        throw std::invalid_argument("simulate_gpu_batch: no --max-seconds (a batch's stacks share their time)");
    if (stacks.size() > 65535) throw std::invalid_argument("simulate_gpu_batch: at most 65535 stacks per batch");
    std::vector<WalkStack> walks;
    int weight_shift = 0;   // one staging scale for the whole batch: the largest any stack needs
    for (const Stack& s : stacks) {
        validate_stack(s);
        walks.push_back(walk_stack_for(s, opt));
        const WalkSpec &w = walks.back().spec, &ws = walks.front().spec;
        weight_shift = std::max(weight_shift, walks.back().weight_shift);
        if (w.layer_count != ws.layer_count || w.base_kind != ws.base_kind)
            throw std::invalid_argument(
                "simulate_gpu_batch: the stacks of a batch must have the same layers and base kind");
        if (opt.specialised && !same_spec(w, ws))
            throw std::invalid_argument(
                "simulate_gpu_batch: stacks with different rough or absorbing layers, or where the "
                "Lambertian series applies to some but not all, need the general walk");
    }
    WalkSpec ws = walks.front().spec;
    // the general walk carries the free-flight code where any stack of the batch scatters (walk.glsl)
    if (!opt.specialised)
        for (const WalkStack& w : walks) ws.scatter_mask |= w.spec.scatter_mask;
    const size_t C = stacks.size();
    std::vector<SimResult> res(C);
    // the same base kind for every stack (checked above), so the same sides
    const WalkGrid grid = walk_grid(opt.dtheta_deg, opt.dphi_deg, opt.orders, stacks[0].transmissive());
    const size_t n_values = grid.values(), n_staging = n_values / 2;
    for (size_t i = 0; i < C; ++i) {
        res[i].stack = stacks[i];
        res[i].options = opt;
        res[i].options.seed = seeds[i];
        res[i].device = ctx.device_info().name;
        res[i].driver = ctx.driver_string();
        res[i].n_theta = grid.n_theta;
        res[i].n_phi = grid.n_phi;
        res[i].n_classes = grid.n_classes;
        res[i].n_sides = grid.n_sides;
    }
    WalkRunner runner(ctx, n_values, C, vk::DescriptorType::eStorageBuffer, C * sizeof(BatchStack),
                      std::to_string(C) + " configurations per batch of this grid");
    BatchStack* live = static_cast<BatchStack*>(runner.stack_mapped());
    for (size_t i = 0; i < C; ++i) {
        walks[i].set_staging_shift(weight_shift);
        BatchStack b{};
        b.stack = walks[i].gpu;
        b.extra = uvec4(seeds[i], 1u, 0u, 0u);   // seed, active
        std::memcpy(&live[i], &b, sizeof b);
    }
    std::unique_ptr<ComputeKernel> sim = runner.make_kernel(simulate_batch_spv, sizeof(simulate_batch_spv));
    build_walk_kernel(*sim, ctx.device(), ws, opt.orders, opt.paths_per_invocation);

    const WalkDispatch wd(opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    // paths per dispatch, per stack: about 2^20 path-stacks per submission (results do not depend on it)
    uint64_t batch =
        std::max<uint64_t>(per_group, std::min<uint64_t>(max_batch, ((1ull << 20) / C / per_group + 1) * per_group));
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        runner.clear();
        WalkPush pc =
            walk_push(grid, opt.dtheta_deg, opt.dphi_deg, opt.max_events, opt.theta_i_deg[a], opt.seed, uint32_t(a));
        pc.staging_stride = uint32_t(n_staging);
        double device_seconds = 0;
        auto t0 = std::chrono::steady_clock::now();
        for (size_t i = 0; i < C; ++i) live[i].extra.y = 1;
        // --rse: as simulate_gpu, paths grow in rounds (next_checkpoint) and a stack stops at the first checkpoint
        // where its relative standard error meets the target, so each stack gets exactly the paths (and bits) of its
        // own simulate_gpu run. Stopped stacks stay in the dispatch but their workgroups return at once.
        std::vector<std::string> stopped_by(C, "paths");
        size_t active = C;
        uint64_t done = 0, checkpoint = next_checkpoint(opt, 0);
        auto angle_of = [&](size_t i, uint64_t paths) {
            AngleResult ar = runner.angle(i, paths);
            ar.theta_i_deg = opt.theta_i_deg[a];
            return ar;
        };
        std::vector<AngleResult> finished(C);
        while (active > 0 && done < opt.paths) {
            uint64_t n = std::min(batch, checkpoint - done);
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            device_seconds += runner.run(*sim, pc, wd.groups(n), uint32_t(C), uint32_t(weight_shift));
            done += n;
            if (opt.rse_target > 0 && done == checkpoint && done < opt.paths) {
                runner.read_back();
                for (size_t i = 0; i < C; ++i) {
                    if (!live[i].extra.y) continue;
                    AngleResult cur = angle_of(i, done);
                    double rse = relative_se_quantile(res[i], cur, opt.rse_quantile);
                    if (rse <= opt.rse_target && rse > 0) {   // as simulate_gpu: stop here
                        live[i].extra.y = 0;
                        active--;
                        stopped_by[i] = "rse";
                        finished[i] = std::move(cur);
                    }
                }
                checkpoint = next_checkpoint(opt, done);
            }
        }
        runner.read_back();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (size_t i = 0; i < C; ++i) {
            AngleResult ar = live[i].extra.y ? angle_of(i, done) : std::move(finished[i]);
            ar.seconds = seconds / double(C);   // shared: each stack's share of the batch
            ar.device_seconds = device_seconds / double(C);
            summarise_relative_se(res[i], ar);
            if (live[i].extra.y) {
                // the last checkpoint is the cap: simulate_gpu reports "rse" there if the target is met
                const double rse = relative_se_quantile(res[i], ar, opt.rse_quantile);
                ar.stopped_by = opt.rse_target > 0 && rse <= opt.rse_target && rse > 0 ? "rse" : "paths";
            } else {
                ar.stopped_by = stopped_by[i];
            }
            res[i].angles.push_back(std::move(ar));
        }
    }
    return res;
}

}   // namespace gonio
