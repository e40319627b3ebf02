// reference_gpu.cpp: simulate_gpu, the walk runner with shaders/simulate.comp: one stack, its incident angles side by
// side in shared dispatches (workgroup row y traces angle y of the dispatch into the histograms of its slot), adaptive
// dispatches, --rse rounds per angle, checkpoints and --resume. A path's random numbers depend on (seed, path index,
// angle index) and every sum is an integer, so an angle's bytes do not depend on which angles share its dispatches.
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
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "simulate_spv.h"

namespace gonio {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// One incident angle while it holds a slot (histograms in the runner).
struct AngleRun {
    size_t index = 0;   // in opt.theta_i_deg: its random stream
    uint32_t slot = 0;
    uint64_t done = 0;   // paths traced, a resumed angle's included
    uint64_t checkpoint = 0;   // where it next stops to look at its sums (next_checkpoint)
    uint64_t staged = 0;   // paths in its staging histogram since the last fold
    uint64_t next = 0;   // its paths in the dispatch being prepared
    double seconds_before = 0;   // a resumed angle's earlier seconds
    double seconds = 0;   // this run's wall clock, each dispatch's shared by paths
    double device_seconds = 0;   // likewise (a resumed angle's earlier ones included)
    double rse = 0;   // at its last --rse check
    WalkPush pc{};   // the angle's push constants (grid, direction, seed mix) and the dispatch's paths
};

// Slots for the run's angles: every angle (or opt.angles_per_dispatch) as far as the device's memory holds their
// histograms; at least one (the runner then says why a grid does not fit).
size_t angle_slots(VkContext& ctx, const SimOptions& opt, size_t n_values) {
    size_t n = opt.theta_i_deg.size();
    if (opt.angles_per_dispatch > 0) n = std::min<size_t>(n, opt.angles_per_dispatch);
    n = std::min<size_t>(n, 65535);   // workgroup rows of one dispatch
    return std::max<size_t>(1, std::min(n, configurations_that_fit(ctx, n_values)));
}

}   // namespace

SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt, const SimResult* resume) {
    validate_options(opt);
    validate_stack(stack);
    if (resume) check_resumable(*resume, stack, opt);
    SimResult res;
    res.stack = stack;
    res.options = opt;
    res.device = ctx.device_info().name;
    res.driver = ctx.driver_string();
    const WalkGrid grid = walk_grid(opt.dtheta_deg, opt.dphi_deg, opt.orders, stack.transmissive());
    res.n_theta = grid.n_theta;
    res.n_phi = grid.n_phi;
    res.n_classes = grid.n_classes;
    res.n_sides = grid.n_sides;
    const size_t n_values = grid.values(), n_angles = opt.theta_i_deg.size();

    const WalkStack walk = walk_stack_for(stack, opt);
    const size_t slots = angle_slots(ctx, opt, n_values);
    WalkRunner runner(ctx, n_values, slots, vk::DescriptorType::eUniformBuffer, sizeof(StackGpu),
                      "a grid of " + std::to_string(res.n_theta) + " x " + std::to_string(res.n_phi) + " bins");
    std::memcpy(runner.stack_mapped(), &walk.gpu, sizeof(walk.gpu));
    runner.clear();
    std::unique_ptr<ComputeKernel> sim = runner.make_kernel(simulate_spv, sizeof(simulate_spv));
    build_walk_kernel(*sim, ctx.device(), walk.spec, opt.orders, opt.paths_per_invocation,
                      opt.baked_stack && can_bake_stack(walk.spec) ? &walk.gpu : nullptr, opt.invalid_path_for_tests);
    const uint32_t shift = uint32_t(walk.staging_shift);

    const WalkDispatch wd(opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    // paths per angle and dispatch
    uint64_t batch =
        opt.batch_paths ? std::min<uint64_t>(opt.batch_paths, max_batch) : std::min<uint64_t>(1u << 16, max_batch);

    Progress progress(opt.progress, stack.name, opt.paths * n_angles);
    auto last_checkpoint = Clock::now();
    uint64_t done_all = 0;
    std::vector<AngleResult> results(n_angles);   // in the order of opt.theta_i_deg
    std::vector<bool> finished(n_angles, false);
    size_t n_finished = 0, next_angle = 0;
    std::vector<AngleRun> active;   // row y of a dispatch traces active[y]
    std::vector<uint32_t> free_slots;
    for (size_t s = slots; s-- > 0;) free_slots.push_back(uint32_t(s));

    auto finish = [&](const AngleRun& r, const char* stopped_by, AngleResult sums) {
        AngleResult& ar = results[r.index];
        ar = std::move(sums);
        ar.theta_i_deg = opt.theta_i_deg[r.index];
        ar.paths = r.done;
        ar.seconds = r.seconds_before + r.seconds;
        ar.device_seconds = r.device_seconds;
        ar.stopped_by = stopped_by;
        summarise_relative_se(res, ar);
        finished[r.index] = true;
        n_finished++;
    };
    // Moves the next angles into free slots. Each starts from zero or from the earlier run's sums, written into its
    // slot's host copy; the host copy then goes to the device whole. Called only where every other slot's host copy
    // is current (after clear() or a read_back(), before any dispatch). A slot not used yet is zero already (clear()).
    std::vector<bool> slot_used(slots, false);
    auto start_angles = [&] {
        bool any = false;
        while (!free_slots.empty() && next_angle < n_angles) {
            AngleRun r;
            r.index = next_angle++;
            r.pc = walk_push(grid, opt.dtheta_deg, opt.dphi_deg, opt.max_events, opt.theta_i_deg[r.index], opt.seed,
                             uint32_t(r.index));
            r.pc.staging_stride = uint32_t(n_values / 2);
            AngleResult prev;   // the earlier run's sums (--resume), else none
            if (resume) {
                const AngleResult& p = resume->angles[r.index];
                prev.raw.assign(p.raw.begin(), p.raw.begin() + std::ptrdiff_t(n_values));
                std::memcpy(prev.energy, p.energy, sizeof(prev.energy));
                prev.paths = r.done = p.paths;
                r.seconds_before = p.seconds;
                r.device_seconds = p.device_seconds;
            }
            // a resumed angle that has its paths is done; one whose paths end a round (--rse) is checked before
            // tracing more, as one uninterrupted run would have checked it there
            if (r.done >= opt.paths) {
                finish(r, "paths", std::move(prev));
                continue;
            }
            if (opt.rse_target > 0 && r.done > 0 && next_checkpoint(opt, r.done - 1) == r.done) {
                r.rse = relative_se_quantile(res, prev, opt.rse_quantile);
                if (r.rse <= opt.rse_target && r.rse > 0) {
                    finish(r, "rse", std::move(prev));
                    continue;
                }
            }
            r.slot = free_slots.back();
            free_slots.pop_back();
            r.checkpoint = next_checkpoint(opt, r.done);
            if (resume) {
                std::memcpy(runner.host_totals(r.slot), prev.raw.data(), n_values * 8);
                std::memcpy(runner.host_energy(r.slot), prev.energy, sizeof(prev.energy));
                any = true;
            } else if (slot_used[r.slot]) {
                std::memset(runner.host_totals(r.slot), 0, n_values * 8);
                std::memset(runner.host_energy(r.slot), 0, sizeof(prev.energy));
                any = true;
            }
            slot_used[r.slot] = true;
            active.push_back(r);
        }
        if (any) runner.upload();
    };
    // Every slot's staging into its totals, and the totals into the host copy (runner.angle reads them).
    auto read_back = [&] {
        bool staged = false;
        for (AngleRun& r : active) staged |= r.staged > 0;
        if (staged) runner.fold_now(shift);
        for (AngleRun& r : active) r.staged = 0;
        runner.read_back();
    };

    start_angles();
    while (!active.empty()) {
        const auto t_step = Clock::now();
        // this dispatch's paths per angle: up to the batch, never past the angle's next checkpoint
        uint64_t total = 0, most = 0;
        bool fold_before = false, at_checkpoint = false;
        WalkAngle* table = runner.angles_mapped();
        for (size_t y = 0; y < active.size(); ++y) {
            AngleRun& r = active[y];
            r.next = std::min(batch, r.checkpoint - r.done);
            total += r.next;
            most = std::max(most, r.next);
            // the packed staging must not carry (bins.glsl): at most MAX_PATHS_PER_DISPATCH paths between folds
            fold_before |= r.staged + r.next > MAX_PATHS_PER_DISPATCH;
            at_checkpoint |= r.done + r.next == r.checkpoint;
            r.pc.path_base_lo = uint32_t(r.done);
            r.pc.path_base_hi = uint32_t(r.done >> 32);
            r.pc.path_count = uint32_t(r.next);
            table[y] = walk_angle(r.pc, r.slot);
        }
        const size_t rows = active.size();
        const auto t_run = Clock::now();
        // a checkpoint reads the sums back, so the dispatch folds its staging after it
        const double device =
            runner.run(*sim, active.front().pc, wd.groups(most), uint32_t(rows), shift, at_checkpoint, fold_before);
        const double dt = seconds_since(t_run);
        done_all += total;
        for (AngleRun& r : active) {
            r.staged = at_checkpoint ? 0 : (fold_before ? 0 : r.staged) + r.next;
            r.done += r.next;
            r.device_seconds += device * double(r.next) / double(total);
        }
        if (at_checkpoint) runner.read_back();
        // checkpoints: an angle stops at the first round whose relative standard error meets the target (--rse), or
        // at its paths
        std::vector<bool> ends(active.size(), false);
        std::vector<const char*> why(active.size(), "paths");
        for (size_t y = 0; y < active.size(); ++y) {
            AngleRun& r = active[y];
            if (r.done != r.checkpoint) continue;
            if (opt.rse_target > 0) {
                r.rse = relative_se_quantile(res, runner.angle(r.slot, r.done), opt.rse_quantile);
                if (r.rse <= opt.rse_target && r.rse > 0) {
                    ends[y] = true;
                    why[y] = "rse";
                    continue;
                }
            }
            if (r.done >= opt.paths)
                ends[y] = true;
            else
                r.checkpoint = next_checkpoint(opt, r.done);
        }
        // the wall clock of this step, shared by paths (one angle alone: all of it, as when angles ran in turn)
        const double step = seconds_since(t_step);
        double worst_rse = 0;   // of the angle furthest from the target
        for (AngleRun& r : active) {
            r.seconds += step * double(r.next) / double(total);
            worst_rse = std::max(worst_rse, r.rse);
        }
        progress.update(done_all,
                        angles_label(opt.theta_i_deg[active.front().index], opt.theta_i_deg[active.back().index],
                                     active.size(), active.front().index, n_finished, n_angles),
                        opt.rse_target > 0 ? worst_rse : -1.0, opt.rse_target);
        // --max-seconds caps each angle's own time (its share of the steps it took part in)
        bool timed_out = false;
        for (size_t y = 0; y < active.size(); ++y)
            if (!ends[y] && opt.max_seconds > 0 && active[y].seconds >= opt.max_seconds && active[y].done < opt.paths) {
                ends[y] = true;
                why[y] = "max_seconds";
                timed_out = true;
            }
        if (timed_out && !at_checkpoint) read_back();   // a checkpoint has folded and read back every slot
        // finished angles leave their slots to the next angles
        bool freed = false;
        std::vector<AngleRun> still;
        for (size_t y = 0; y < active.size(); ++y) {
            if (!ends[y]) {
                still.push_back(active[y]);
                continue;
            }
            finish(active[y], why[y], runner.angle(active[y].slot, active[y].done));
            free_slots.push_back(active[y].slot);
            freed = true;
        }
        active = std::move(still);
        if (freed) start_angles();   // the host copy is current: read back above
        if (opt.on_checkpoint && !active.empty() && seconds_since(last_checkpoint) >= opt.checkpoint_seconds) {
            read_back();
            // the finished angles, those in slots so far, the others as they were before this run
            SimResult partial = res;
            partial.angles.resize(n_angles);
            for (size_t a = 0; a < n_angles; ++a) {
                if (finished[a]) {
                    partial.angles[a] = results[a];
                } else if (resume) {
                    partial.angles[a] = resume->angles[a];
                } else {
                    partial.angles[a].raw.assign(n_values, 0);
                }
                partial.angles[a].theta_i_deg = opt.theta_i_deg[a];
            }
            for (const AngleRun& r : active) {
                AngleResult cur = runner.angle(r.slot, r.done);
                cur.theta_i_deg = opt.theta_i_deg[r.index];
                cur.seconds = r.seconds_before + r.seconds;
                cur.device_seconds = r.device_seconds;
                cur.stopped_by = "checkpoint";
                partial.angles[r.index] = std::move(cur);
            }
            opt.on_checkpoint(partial);
            last_checkpoint = Clock::now();
        }
        // adapt the batch towards ~0.25 s per submission and angle, up to 2 s per submission (results do not depend
        // on it): each row of a dispatch brings its angle's staging histogram back into the caches (on lavapipe the
        // CPU's), so rows of a few paths each would pay that on every dispatch (measured: 4 % at 0.25 s per submission)
        if (!opt.batch_paths && dt > 0.0 && !active.empty()) {
            const double seconds = 0.25 * double(std::min<size_t>(rows, 8));
            double target = double(total) * seconds / dt / double(rows);
            uint64_t next = uint64_t(std::clamp(target, double(per_group), double(most) * 4.0));
            batch = std::min<uint64_t>(std::max<uint64_t>(next / per_group, 1) * per_group, max_batch);
        }
    }
    progress.finish();
    res.angles = std::move(results);
    return res;
}

}   // namespace gonio
