// angle_policy.cpp: see angle_policy.h.
#include "angle_policy.h"

#include <cmath>

namespace gonio {

WalkGrid walk_grid(double dtheta_deg, double dphi_deg, bool orders, bool transmissive) {
    WalkGrid g;
    g.n_theta = uint32_t(std::lround(90.0 / dtheta_deg));
    g.n_phi = uint32_t(std::lround(360.0 / dphi_deg));
    g.n_classes = orders ? 3 : 1;
    g.n_sides = transmissive ? 2 : 1;
    return g;
}

SimResult start_result(const Stack& stack, const SimOptions& opt, const std::string& device, const std::string& driver,
                       const WalkGrid& grid, const WalkRan& walk) {
    SimResult r;
    r.stack = stack;
    r.options = opt;
    r.device = device;
    r.driver = driver;
    r.n_theta = grid.n_theta;
    r.n_phi = grid.n_phi;
    r.n_classes = grid.n_classes;
    r.n_sides = grid.n_sides;
    r.walk = walk;
    return r;
}

WalkRan walk_ran(const WalkStack& w, const SimOptions& opt, bool host_bakes) {
    return {w.spec.specialised, host_bakes && opt.baked_stack && can_bake_stack(w.spec), w.spec.series,
            w.spec.entry_branch, w.spec.exit_estimates};
}

}   // namespace gonio
