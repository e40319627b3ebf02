// reference_gpu.cpp: simulate_gpu, the walk runner with shaders/simulate.comp: one stack, its incident angles side by
// side in shared dispatches (workgroup row y traces angle y of the dispatch into the histograms of its slot), adaptive
// dispatches, --rse rounds per angle, checkpoints and --resume (the stopping rules: angle_policy.h). A path's random
// numbers depend on (seed, path index, angle index) and every sum is an integer, so an angle's bytes do not depend on
// which angles share its dispatches.
#include "angle_policy.h"
#include "compute_kernel.h"
#include "histogram.h"
#include "progress.h"
#include "reference.h"
#include "stack_gpu.h"
#include "vk_context.h"
#include "walk_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "walk_spirv.h"

namespace gonio {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// One incident angle while it holds a slot (histograms in the runner).
struct AngleRun {
    size_t index = 0;   // in opt.theta_i_deg: its random stream
    uint32_t slot = 0;
    uint64_t done = 0;   // paths traced, a resumed angle's included
    uint64_t checkpoint = 0;   // where it next stops to look at its sums (AnglePolicy::next_checkpoint)
    uint64_t staged = 0;   // paths in its staging histogram since the last fold
    uint64_t next = 0;   // its paths in the dispatch being prepared
    double seconds_before = 0;   // a resumed angle's earlier seconds
    double seconds = 0;   // this run's wall clock, each dispatch's shared by paths
    double device_seconds = 0;   // likewise (a resumed angle's earlier ones included)
    double rse = 0;   // at its last --rse check
    WalkPush pc{};   // the angle's push constants (grid, direction, seed mix) and the dispatch's paths
    bool ends = false;   // at the step just run: it stops, for `why`
    const char* why = "paths";
};

// Slots for the run's angles: every angle (or opt.angles_per_dispatch) as far as the device's memory holds their
// histograms; at least one (the runner then says why a grid does not fit).
size_t angle_slots(VkContext& ctx, const SimOptions& opt, size_t n_values) {
    size_t n = opt.theta_i_deg.size();
    if (opt.angles_per_dispatch > 0) n = std::min<size_t>(n, opt.angles_per_dispatch);
    n = std::min<size_t>(n, 65535);   // workgroup rows of one dispatch
    return std::max<size_t>(1, std::min(n, configurations_that_fit(ctx, n_values)));
}

// simulate_gpu's state: the runner and its kernel, the angles in slots, those waiting, those finished.
class GpuRun {
public:
    GpuRun(VkContext& ctx, const Stack& stack, const SimOptions& opt, const SimResult* resume);
    SimResult run();

private:
    const SimOptions& opt;
    const AnglePolicy policy;
    const SimResult* resume;
    const WalkGrid grid;
    const size_t n_values, n_angles;
    const WalkStack walk;
    SimResult res;
    WalkRunner runner;
    std::unique_ptr<ComputeKernel> sim;
    const WalkDispatch wd;
    uint64_t batch;   // paths per angle and dispatch
    Progress progress;
    Clock::time_point last_checkpoint = Clock::now();
    uint64_t done_all = 0;
    std::vector<AngleResult> results;   // in the order of opt.theta_i_deg
    std::vector<bool> finished, slot_used;
    size_t n_finished = 0, next_angle = 0;
    std::vector<AngleRun> active;   // row y of a dispatch traces active[y]
    std::vector<uint32_t> free_slots;

    void finish(const AngleRun& r, const char* stopped_by, AngleResult sums);
    void start_angles();
    AngleResult resumed_sums(AngleRun& r) const;
    void read_back();
    void step();
    void check_rounds();
    void check_time(bool at_checkpoint);
    void free_finished();
    void write_checkpoint();
};

GpuRun::GpuRun(VkContext& ctx, const Stack& stack, const SimOptions& o, const SimResult* resume_)
    : opt(o),
      policy{o},
      resume(resume_),
      grid(walk_grid(o.dtheta_deg, o.dphi_deg, o.orders, stack.transmissive())),
      n_values(grid.values()),
      n_angles(o.theta_i_deg.size()),
      walk(walk_stack_for(stack, o)),
      res(start_result(stack, o, ctx.device_info().name, ctx.driver_string(), grid, walk_ran(walk, o, true))),
      runner(ctx, n_values, angle_slots(ctx, o, n_values), vk::DescriptorType::eUniformBuffer, sizeof(StackGpu),
             "a grid of " + std::to_string(grid.n_theta) + " x " + std::to_string(grid.n_phi) + " bins"),
      wd(o.paths_per_invocation),
      progress(o.progress, stack.name, o.paths * n_angles),
      results(n_angles),
      finished(n_angles, false) {
    std::memcpy(runner.stack_mapped(), &walk.gpu, sizeof(walk.gpu));
    runner.clear();
    const Spirv spv = walk_spirv(walk.spec, WalkShader::one_stack);
    sim = runner.make_kernel(spv.words, spv.bytes);
    build_walk_kernel(*sim, ctx.device(), walk.spec, opt.orders, opt.paths_per_invocation, opt.phi_i_deg != 0.0,
                      res.walk.baked_stack ? &walk.gpu : nullptr, opt.invalid_path_for_tests, opt.fault_for_tests);
    batch = opt.batch_paths ? std::min<uint64_t>(opt.batch_paths, wd.max_paths)
                            : std::min<uint64_t>(1u << 16, wd.max_paths);
    const size_t slots = runner.configurations();
    slot_used.assign(slots, false);
    for (size_t s = slots; s-- > 0;) free_slots.push_back(uint32_t(s));
}

void GpuRun::finish(const AngleRun& r, const char* stopped_by, AngleResult sums) {
    AngleResult& ar = results[r.index];
    ar = std::move(sums);
    ar.theta_i_deg = opt.theta_i_deg[r.index];
    ar.phi_i_deg = opt.phi_i_deg;
    ar.paths = r.done;
    ar.seconds = r.seconds_before + r.seconds;
    ar.device_seconds = r.device_seconds;
    ar.stopped_by = stopped_by;
    summarise_relative_se(res, ar);
    finished[r.index] = true;
    n_finished++;
}

// The earlier run's sums of angle r (--resume), with its paths and times; else none
AngleResult GpuRun::resumed_sums(AngleRun& r) const {
    AngleResult prev;
    if (!resume) return prev;
    const AngleResult& p = resume->angles[r.index];
    prev.raw.assign(p.raw.begin(), p.raw.begin() + std::ptrdiff_t(n_values));
    std::memcpy(prev.energy, p.energy, sizeof(prev.energy));
    prev.paths = r.done = p.paths;
    r.seconds_before = p.seconds;
    r.device_seconds = p.device_seconds;
    return prev;
}

// Moves the next angles into free slots. Each starts from zero or from the earlier run's sums, written into its
// slot's host copy; the host copy then goes to the device whole. Called only where every other slot's host copy is
// current (after clear() or a read_back(), before any dispatch). A slot not used yet is zero already (clear()).
void GpuRun::start_angles() {
    bool any = false;
    while (!free_slots.empty() && next_angle < n_angles) {
        AngleRun r;
        r.index = next_angle++;
        r.pc = walk_push(grid, opt.dtheta_deg, opt.dphi_deg, opt.max_events, opt.theta_i_deg[r.index], opt.phi_i_deg,
                         opt.seed, uint32_t(r.index));
        r.pc.staging_stride = uint32_t(n_values / 2);
        AngleResult prev = resumed_sums(r);
        // a resumed angle that has its paths is done; one whose paths end a round (--rse) is checked before tracing
        // more, as one uninterrupted run would have checked it there
        if (r.done >= opt.paths) {
            finish(r, "paths", std::move(prev));
            continue;
        }
        if (policy.at_round_end(r.done)) {
            r.rse = policy.rse(res, prev);
            if (policy.rse_met(r.rse)) {
                finish(r, "rse", std::move(prev));
                continue;
            }
        }
        r.slot = free_slots.back();
        free_slots.pop_back();
        r.checkpoint = policy.next_checkpoint(r.done);
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
}

// Every slot's staging into its totals, and the totals into the host copy (runner.angle reads them).
void GpuRun::read_back() {
    bool staged = false;
    for (AngleRun& r : active) staged |= r.staged > 0;
    if (staged) runner.fold_now(uint32_t(walk.staging_shift));
    for (AngleRun& r : active) r.staged = 0;
    runner.read_back();
}

// At a checkpoint an angle stops at the first round whose relative standard error meets the target (--rse), or at
// its paths.
void GpuRun::check_rounds() {
    for (AngleRun& r : active) {
        r.ends = false;
        r.why = "paths";
        if (r.done != r.checkpoint) continue;
        if (opt.rse_target > 0) {
            r.rse = policy.rse(res, runner.angle(r.slot, r.done));
            if (policy.rse_met(r.rse)) {
                r.ends = true;
                r.why = "rse";
                continue;
            }
        }
        if (r.done >= opt.paths)
            r.ends = true;
        else
            r.checkpoint = policy.next_checkpoint(r.done);
    }
}

// --max-seconds caps each angle's own time (its share of the steps it took part in).
void GpuRun::check_time(bool at_checkpoint) {
    bool timed_out = false;
    for (AngleRun& r : active)
        if (!r.ends && policy.out_of_time(r.seconds, r.done)) {
            r.ends = true;
            r.why = "max_seconds";
            timed_out = true;
        }
    if (timed_out && !at_checkpoint) read_back();   // a checkpoint has folded and read back every slot
}

// Finished angles leave their slots to the next angles.
void GpuRun::free_finished() {
    bool freed = false;
    std::vector<AngleRun> still;
    for (const AngleRun& r : active) {
        if (!r.ends) {
            still.push_back(r);
            continue;
        }
        finish(r, r.why, runner.angle(r.slot, r.done));
        free_slots.push_back(r.slot);
        freed = true;
    }
    active = std::move(still);
    if (freed) start_angles();   // the host copy is current: read back before
}

// The run so far for opt.on_checkpoint: the finished angles, those in slots so far, the others as they were before
// this run.
void GpuRun::write_checkpoint() {
    read_back();
    SimResult partial = res;
    partial.angles.resize(n_angles);
    for (size_t a = 0; a < n_angles; ++a) {
        if (finished[a])
            partial.angles[a] = results[a];
        else if (resume)
            partial.angles[a] = resume->angles[a];
        else
            partial.angles[a].raw.assign(n_values, 0);
        partial.angles[a].theta_i_deg = opt.theta_i_deg[a];
        partial.angles[a].phi_i_deg = opt.phi_i_deg;
    }
    for (const AngleRun& r : active) {
        AngleResult cur = runner.angle(r.slot, r.done);
        cur.theta_i_deg = opt.theta_i_deg[r.index];
        cur.phi_i_deg = opt.phi_i_deg;
        cur.seconds = r.seconds_before + r.seconds;
        cur.device_seconds = r.device_seconds;
        cur.stopped_by = "checkpoint";
        partial.angles[r.index] = std::move(cur);
    }
    opt.on_checkpoint(partial);
    last_checkpoint = Clock::now();
}

// One dispatch of every active angle, up to the batch and never past an angle's next checkpoint; then the
// checkpoints, the finished angles, the progress line, the run's checkpoint and the next batch size.
void GpuRun::step() {
    const auto t_step = Clock::now();
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
    const double device = runner.run(*sim, active.front().pc, wd.groups(most), uint32_t(rows),
                                     uint32_t(walk.staging_shift), at_checkpoint, fold_before);
    const double dt = seconds_since(t_run);
    done_all += total;
    for (AngleRun& r : active) {
        r.staged = at_checkpoint ? 0 : (fold_before ? 0 : r.staged) + r.next;
        r.done += r.next;
        r.device_seconds += device * double(r.next) / double(total);
    }
    if (at_checkpoint) runner.read_back();
    check_rounds();
    // the wall clock of this step, shared by paths (one angle alone: all of it, as when angles ran in turn)
    const double step_seconds = seconds_since(t_step);
    double worst_rse = 0;   // of the angle furthest from the target
    for (AngleRun& r : active) {
        r.seconds += step_seconds * double(r.next) / double(total);
        worst_rse = std::max(worst_rse, r.rse);
    }
    progress.update(done_all,
                    angles_label(opt.theta_i_deg[active.front().index], opt.theta_i_deg[active.back().index],
                                 active.size(), active.front().index, n_finished, n_angles),
                    opt.rse_target > 0 ? worst_rse : -1.0, opt.rse_target);
    if (opt.on_progress) opt.on_progress(done_all, opt.paths * n_angles);
    check_time(at_checkpoint);
    free_finished();
    if (opt.on_checkpoint && !active.empty() && seconds_since(last_checkpoint) >= opt.checkpoint_seconds)
        write_checkpoint();
    // adapt the batch towards ~0.25 s per submission and angle, up to 2 s per submission (results do not depend on
    // it): each row of a dispatch brings its angle's staging histogram back into the caches (on lavapipe the CPU's),
    // so rows of a few paths each would pay that on every dispatch (measured: 4 % at 0.25 s per submission)
    if (!opt.batch_paths && dt > 0.0 && !active.empty()) {
        const double seconds = 0.25 * double(std::min<size_t>(rows, 8));
        double target = double(total) * seconds / dt / double(rows);
        uint64_t next = uint64_t(std::clamp(target, double(wd.per_group), double(most) * 4.0));
        batch = std::min<uint64_t>(std::max<uint64_t>(next / wd.per_group, 1) * wd.per_group, wd.max_paths);
    }
}

SimResult GpuRun::run() {
    start_angles();
    while (!active.empty()) step();
    progress.finish();
    res.angles = std::move(results);
    return std::move(res);
}

}   // namespace

SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt, const SimResult* resume) {
    validate_options(opt);
    validate_stack(stack);
    if (resume) check_resumable(*resume, stack, opt);
    return GpuRun(ctx, stack, opt, resume).run();
}

}   // namespace gonio
