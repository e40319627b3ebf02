// reference_gpu.cpp: simulate_gpu, the walk runner with shaders/simulate.comp: one stack, its incident angles in
// turn, adaptive dispatches, --rse rounds, checkpoints and --resume.
#include "reference.h"
#include "state.h"
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
    const size_t n_values = grid.values();

    const WalkStack walk = walk_stack_for(stack, opt);
    WalkRunner runner(ctx, n_values, 1, vk::DescriptorType::eUniformBuffer, sizeof(StackGpu),
                      "a grid of " + std::to_string(res.n_theta) + " x " + std::to_string(res.n_phi) + " bins");
    std::memcpy(runner.stack_mapped(), &walk.gpu, sizeof(walk.gpu));
    runner.clear();
    std::unique_ptr<ComputeKernel> sim = runner.make_kernel(simulate_spv, sizeof(simulate_spv));
    build_walk_kernel(*sim, ctx.device(), walk.spec, opt.orders, opt.paths_per_invocation,
                      opt.baked_stack && can_bake_stack(walk.spec) ? &walk.gpu : nullptr, opt.invalid_path_for_tests);

    const WalkDispatch wd(opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    uint64_t batch =
        opt.batch_paths ? std::min<uint64_t>(opt.batch_paths, max_batch) : std::min<uint64_t>(1u << 16, max_batch);

    Progress progress(opt.progress, stack.name, opt.paths * opt.theta_i_deg.size());
    auto last_checkpoint = std::chrono::steady_clock::now();
    uint64_t done_all = 0;
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        AngleResult ar;
        ar.theta_i_deg = opt.theta_i_deg[a];
        std::memset(runner.host_totals(), 0, n_values * 8);
        std::memset(runner.host_energy(), 0, kEnergyEntries * 8);
        uint64_t done = 0;
        if (resume) {   // continue the earlier run's sums and path numbering
            const AngleResult& prev = resume->angles[a];
            std::memcpy(runner.host_totals(), prev.raw.data(), n_values * 8);
            std::memcpy(runner.host_energy(), prev.energy, sizeof(prev.energy));
            done = prev.paths;
            ar.seconds = prev.seconds;
            ar.device_seconds = prev.device_seconds;
        }
        runner.upload();
        uint64_t checkpoint = next_checkpoint(opt, done);
        auto snapshot = [&](uint64_t paths) {
            runner.read_back();
            return runner.angle(0, paths);
        };
        double shown_rse = 0.0;
        WalkPush pc =
            walk_push(grid, opt.dtheta_deg, opt.dphi_deg, opt.max_events, opt.theta_i_deg[a], opt.seed, uint32_t(a));
        auto t0 = std::chrono::steady_clock::now();
        const double seconds_before = ar.seconds;
        // a resumed angle whose paths end a round (--rse) is checked before tracing more, as one uninterrupted run
        // would have checked it there
        if (opt.rse_target > 0 && done > 0 && done < opt.paths && next_checkpoint(opt, done - 1) == done) {
            shown_rse = relative_se_quantile(res, snapshot(done), opt.rse_quantile);
            if (shown_rse <= opt.rse_target && shown_rse > 0) ar.stopped_by = "rse";
        }
        while (done < opt.paths && ar.stopped_by != "rse") {
            uint64_t n = std::min(batch, checkpoint - done);
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            auto b0 = std::chrono::steady_clock::now();
            ar.device_seconds += runner.run(*sim, pc, wd.groups(n), 1, uint32_t(walk.staging_shift));
            double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count();
            done += n;
            done_all += n;
            double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (opt.rse_target > 0 && done == checkpoint) {
                shown_rse = relative_se_quantile(res, snapshot(done), opt.rse_quantile);
                if (shown_rse <= opt.rse_target && shown_rse > 0) {
                    ar.stopped_by = "rse";
                    break;
                }
                checkpoint = next_checkpoint(opt, done);
            }
            progress.update(done_all, a, opt.theta_i_deg.size(), opt.theta_i_deg[a],
                            opt.rse_target > 0 ? shown_rse : -1.0, opt.rse_target);
            if (opt.max_seconds > 0 && elapsed >= opt.max_seconds && done < opt.paths) {
                ar.stopped_by = "max_seconds";
                break;
            }
            if (opt.on_checkpoint && done < opt.paths &&
                std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
                    opt.checkpoint_seconds) {
                SimResult partial = res;   // the angles done, this one so far, the others as they were before this run
                AngleResult cur = snapshot(done);
                cur.theta_i_deg = ar.theta_i_deg;
                cur.seconds = seconds_before + elapsed;
                cur.device_seconds = ar.device_seconds;
                cur.stopped_by = "checkpoint";
                partial.angles.push_back(std::move(cur));
                for (size_t b = a + 1; b < opt.theta_i_deg.size(); ++b) {
                    AngleResult later;
                    if (resume)
                        later = resume->angles[b];
                    else
                        later.raw.assign(n_values, 0);
                    later.theta_i_deg = opt.theta_i_deg[b];
                    partial.angles.push_back(std::move(later));
                }
                opt.on_checkpoint(partial);
                last_checkpoint = std::chrono::steady_clock::now();
            }
            // adapt the batch towards ~0.25 s per submission (results do not depend on it)
            if (!opt.batch_paths && dt > 0.0) {
                double target = double(n) * 0.25 / dt;
                uint64_t next = uint64_t(std::clamp(target, double(per_group), double(n) * 4.0));
                batch = std::min<uint64_t>(std::max<uint64_t>(next / per_group, 1) * per_group, max_batch);
            }
        }
        ar.seconds = seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        AngleResult fin = snapshot(done);
        ar.paths = done;
        ar.raw = std::move(fin.raw);
        std::memcpy(ar.energy, fin.energy, sizeof(ar.energy));
        summarise_relative_se(res, ar);
        res.angles.push_back(std::move(ar));
    }
    progress.finish();
    return res;
}

}   // namespace gonio
