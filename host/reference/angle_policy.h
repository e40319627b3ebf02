// angle_policy.h: how a reference run goes about its incident angles, written once for simulate_gpu, the sweeps'
// batch, the CPU twin and the viewer's session: the histogram's grid, the result a run starts from (with the walk it
// runs, recorded by the host that runs it), the checkpoints where an angle's sums are looked at (the --rse rounds),
// and when an angle stops: its --rse target at the quantile, its paths, its time (--max-seconds).
#pragma once
#include "histogram.h"
#include "reference.h"

#include <cstdint>
#include <string>

namespace gonio {

// The histogram of a run: bins, path classes and sides.
struct WalkGrid {
    uint32_t n_theta = 0, n_phi = 0, n_classes = 1;
    uint32_t n_sides = 2;   // 2 (reflection, transmission), 1 for an opaque stack
    size_t values() const { return size_t(n_classes) * n_sides * n_theta * n_phi * 6; }   // raw totals
};
WalkGrid walk_grid(double dtheta_deg, double dphi_deg, bool orders, bool transmissive);

// A run's result before its first path: the stack, the options, the device, the grid and the walk it runs.
SimResult start_result(const Stack& stack, const SimOptions& opt, const std::string& device, const std::string& driver,
                       const WalkGrid& grid, const WalkRan& walk);
// What walk these options run on this stack (walk_stack_for), baked where the host bakes it (simulate_gpu does,
// where can_bake_stack; the batch, the CPU twin and the viewer never).
WalkRan walk_ran(const WalkStack& w, const SimOptions& opt, bool host_bakes);

// --rse: the paths grow in rounds that end at 2^20 x 2^k paths (capped by `cap`), where the target is checked, so
// the stopping point does not depend on the dispatch sizes: the end of the round after `from` paths.
inline uint64_t rse_round_end(uint64_t from, uint64_t cap) {
    uint64_t c = 1u << 20;
    while (c <= from) c *= 2;
    return std::min(c, cap);
}

struct AnglePolicy {
    const SimOptions& opt;
    // Where an angle next stops to look at its sums after `from` paths: the end of the round (--rse), else the cap.
    uint64_t next_checkpoint(uint64_t from) const {
        return opt.rse_target > 0 ? rse_round_end(from, opt.paths) : opt.paths;
    }
    // Whether `done` paths end a round whose sums are looked at (a resumed angle is checked there before tracing)
    bool at_round_end(uint64_t done) const {
        return opt.rse_target > 0 && done > 0 && next_checkpoint(done - 1) == done;
    }
    // The relative standard error the --rse target is checked on, and whether it meets the target (0: no bins)
    double rse(const SimResult& r, const AngleResult& a) const { return relative_se_quantile(r, a, opt.rse_quantile); }
    bool rse_met(double rse) const { return opt.rse_target > 0 && rse <= opt.rse_target && rse > 0; }
    // --max-seconds: an angle that has used its time and not its paths stops
    bool out_of_time(double seconds, uint64_t done) const {
        return opt.max_seconds > 0 && seconds >= opt.max_seconds && done < opt.paths;
    }
};

}   // namespace gonio
