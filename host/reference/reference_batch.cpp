// reference_batch.cpp: simulate_gpu_batch, the walk runner with shaders/simulate_batch.comp: many stacks per
// dispatch (see reference.h).
#include "angle_policy.h"
#include "reference.h"
#include "compute_kernel.h"
#include "histogram.h"
#include "progress.h"
#include "stack_gpu.h"
#include "vk_context.h"
#include "walk_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <stdexcept>

#include "walk_spirv.h"

namespace gonio {

namespace {

// Whether walks of these two specs can share one batch's kernel: the same layers and base kind (so the same sides),
// and for the specialised walk the same specialisation. The reason they cannot, empty where they can.
std::string kernel_mismatch(const WalkSpec& w, const WalkSpec& w0, bool specialised) {
    if (w.layer_count != w0.layer_count || w.base_kind != w0.base_kind)
        return "the stacks of a batch must have the same layers and base kind";
    if (specialised && !(w == w0))
        return "stacks with different rough or absorbing layers or microsurfaces, or where the Lambertian series "
               "applies to some but not all, need the general walk";
    return "";
}

// The stacks' walks, checked to share one kernel (kernel_mismatch); one staging scale for the whole batch, the largest
// any stack needs.
std::vector<WalkStack> batch_walks(const std::vector<Stack>& stacks, const SimOptions& opt, WalkSpec& ws) {
    std::vector<WalkStack> walks;
    int weight_shift = 0;
    for (const Stack& s : stacks) {
        validate_stack(s);
        walks.push_back(walk_stack_for(s, opt));
        const WalkSpec &w = walks.back().spec, &w0 = walks.front().spec;
        weight_shift = std::max(weight_shift, walks.back().weight_shift);
        if (const std::string why = kernel_mismatch(w, w0, opt.specialised); !why.empty())
            throw std::invalid_argument("simulate_gpu_batch: " + why);
    }
    for (WalkStack& w : walks) w.set_staging_shift(weight_shift);
    ws = walks.front().spec;
    // the general walk carries the free-flight code where any stack of the batch scatters, and the other
    // microsurfaces' where any stack has one (walk.glsl)
    if (!opt.specialised)
        for (const WalkStack& w : walks) {
            ws.scatter_mask |= w.spec.scatter_mask;
            ws.microsurface_mask |= w.spec.microsurface_mask;
            ws.multiple_mask |= w.spec.multiple_mask;
            ws.microflake_mask |= w.spec.microflake_mask;
        }
    return walks;
}

// One incident angle of every stack of the batch: dispatches until each stack has its paths (caps[i]) or met its --rse
// target at a checkpoint (as simulate_gpu: paths grow in rounds and a stack stops at the first checkpoint where its
// relative standard error meets the target, so each stack gets exactly the paths and bits of its own simulate_gpu
// run; stopped stacks stay in the dispatch but their workgroups return at once).
struct BatchAngle {
    WalkRunner& runner;
    const ComputeKernel& sim;
    const SimOptions& opt;
    const std::vector<uint64_t>& caps;
    std::vector<SimResult>& res;
    BatchStack* live;
    uint32_t shift;
    uint64_t batch;
    Progress& progress;
    uint64_t& progress_done;
    uint64_t progress_total;   // for opt.on_progress

    // the next place where the dispatches stop after `done` paths: a dispatch's end, the --rse round's end, or a
    // live stack's paths
    uint64_t next_stop(uint64_t done, uint64_t most) const {
        uint64_t stop = std::min(done + batch, opt.rse_target > 0 ? rse_round_end(done, most) : most);
        for (size_t i = 0; i < res.size(); ++i)
            if (live[i].extra.y) stop = std::min(stop, caps[i]);
        return stop;
    }

    void run(size_t a, const WalkGrid& grid) {
        const AnglePolicy policy{opt};
        const size_t C = res.size();
        const WalkDispatch wd(opt.paths_per_invocation);
        runner.clear();
        WalkPush pc = walk_push(grid, opt.dtheta_deg, opt.dphi_deg, opt.max_events, opt.theta_i_deg[a], opt.phi_i_deg,
                                opt.seed, uint32_t(a));
        pc.staging_stride = uint32_t(grid.values() / 2);
        double device_seconds = 0;
        const auto t0 = std::chrono::steady_clock::now();
        for (size_t i = 0; i < C; ++i) live[i].extra.y = 1;
        const uint64_t most = *std::max_element(caps.begin(), caps.end());
        std::vector<std::string> stopped_by(C, "paths");
        std::vector<AngleResult> finished(C);
        size_t active = C;
        uint64_t done = 0;
        auto angle_of = [&](size_t i, uint64_t paths) {
            AngleResult ar = runner.angle(i, paths);
            ar.theta_i_deg = opt.theta_i_deg[a];
            ar.phi_i_deg = opt.phi_i_deg;
            return ar;
        };
        while (active > 0) {
            const uint64_t stop = next_stop(done, most), n = stop - done;
            size_t rows = 0;
            for (size_t i = 0; i < C; ++i) rows += live[i].extra.y;
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            device_seconds += runner.run(sim, pc, wd.groups(n), uint32_t(C), shift);
            done = stop;
            progress_done += n * rows;
            progress.update(progress_done,
                            angles_label(opt.theta_i_deg[a], opt.theta_i_deg[a], 1, a, a, opt.theta_i_deg.size()));
            if (opt.on_progress) opt.on_progress(progress_done, progress_total);
            const bool round_end = opt.rse_target > 0 && done == rse_round_end(done - 1, most);
            bool look = false;
            for (size_t i = 0; i < C; ++i) look |= live[i].extra.y && (done == caps[i] || round_end);
            if (!look) continue;
            runner.read_back();
            for (size_t i = 0; i < C; ++i) {
                if (!live[i].extra.y) continue;
                if (done == caps[i]) {   // its paths: the last checkpoint, where simulate_gpu reports "rse" if met
                    finished[i] = angle_of(i, done);
                    summarise_relative_se(res[i], finished[i]);
                    stopped_by[i] = policy.rse_met(policy.rse(res[i], finished[i])) ? "rse" : "paths";
                } else {
                    AngleResult cur = angle_of(i, done);
                    if (!policy.rse_met(policy.rse(res[i], cur))) continue;
                    finished[i] = std::move(cur);   // as simulate_gpu: stop here
                    summarise_relative_se(res[i], finished[i]);
                    stopped_by[i] = "rse";
                }
                live[i].extra.y = 0;
                active--;
            }
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        uint64_t traced = 0;
        for (const AngleResult& ar : finished) traced += ar.paths;
        for (size_t i = 0; i < C; ++i) {
            AngleResult& ar = finished[i];
            const double share = double(ar.paths) / double(std::max<uint64_t>(traced, 1));   // of the batch's time
            ar.seconds = seconds * share;
            ar.device_seconds = device_seconds * share;
            ar.stopped_by = stopped_by[i];
            res[i].angles.push_back(std::move(ar));
        }
    }
};

}   // namespace

std::vector<SimResult> simulate_gpu_batch(VkContext& ctx, const std::vector<Stack>& stacks,
                                          const std::vector<uint32_t>& seeds, const SimOptions& opt,
                                          const std::vector<uint64_t>& paths) {
    validate_options(opt);
    if (stacks.empty()) return {};
    if (seeds.size() != stacks.size()) throw std::invalid_argument("simulate_gpu_batch: one seed per stack");
    if (!paths.empty() && paths.size() != stacks.size())
        throw std::invalid_argument("simulate_gpu_batch: one path count per stack, or none");
    if (opt.max_seconds > 0)
        throw std::invalid_argument("simulate_gpu_batch: no --max-seconds (a batch's stacks share their time)");
    if (stacks.size() > 65535) throw std::invalid_argument("simulate_gpu_batch: at most 65535 stacks per batch");
    const std::vector<uint64_t> caps = paths.empty() ? std::vector<uint64_t>(stacks.size(), opt.paths) : paths;
    for (uint64_t n : caps) {
        SimOptions o = opt;
        o.paths = n;
        validate_options(o);
    }
    WalkSpec ws;
    const std::vector<WalkStack> walks = batch_walks(stacks, opt, ws);
    const size_t C = stacks.size();
    // the same base kind for every stack (checked above), so the same sides
    const WalkGrid grid = walk_grid(opt.dtheta_deg, opt.dphi_deg, opt.orders, stacks[0].transmissive());
    std::vector<SimResult> res;
    uint64_t total = 0;
    for (size_t i = 0; i < C; ++i) {
        SimOptions o = opt;
        o.seed = seeds[i];
        o.paths = caps[i];
        total += caps[i] * opt.theta_i_deg.size();
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
    const Spirv spv = walk_spirv(ws, WalkShader::batch);
    std::unique_ptr<ComputeKernel> sim = runner.make_kernel(spv.words, spv.bytes);
    build_walk_kernel(*sim, ctx.device(), ws, opt.orders, opt.paths_per_invocation, opt.phi_i_deg != 0.0);
    const WalkDispatch wd(opt.paths_per_invocation);
    // paths per dispatch, per stack: about 2^20 path-stacks per submission (results do not depend on it)
    const uint64_t batch = std::max<uint64_t>(
        wd.per_group, std::min<uint64_t>(wd.max_paths, ((1ull << 20) / C / wd.per_group + 1) * wd.per_group));
    Progress progress(opt.progress, std::to_string(C) + " stacks in one batch", total);
    uint64_t progress_done = 0;
    BatchAngle angle{runner, *sim,     opt,           caps, res, live, uint32_t(walks.front().staging_shift),
                     batch,  progress, progress_done, total};
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) angle.run(a, grid);
    progress.finish();
    return res;
}

std::vector<std::vector<size_t>> batch_groups(VkContext& ctx, const std::vector<Stack>& stacks, const SimOptions& opt) {
    std::vector<std::vector<size_t>> groups;
    if (stacks.empty()) return groups;
    const WalkGrid grid = walk_grid(opt.dtheta_deg, opt.dphi_deg, opt.orders, stacks.front().transmissive());
    const size_t most = std::max<size_t>(1, configurations_that_fit(ctx, grid.values()));
    std::vector<WalkSpec> specs;   // of each group's first stack
    for (size_t i = 0; i < stacks.size(); ++i) {
        const WalkSpec w = walk_stack_for(stacks[i], opt).spec;
        size_t g = 0;
        for (; g < groups.size(); ++g)
            if (kernel_mismatch(w, specs[g], opt.specialised).empty() && groups[g].size() < most) break;
        if (g == groups.size()) {
            groups.emplace_back();
            specs.push_back(w);
        }
        groups[g].push_back(i);
    }
    return groups;
}

}   // namespace gonio
