// sim_options.cpp: see sim_options.h.
#include "sim_options.h"
#include "reference.h"
#include "text_format.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gonio {

void validate_options(const SimOptions& o) {
    auto divides = [](double w, double range) {
        double n = range / w;
        return w > 0 && std::fabs(n - std::round(n)) < 1e-9 && n >= 1;
    };
    if (o.theta_i_deg.empty()) throw std::invalid_argument("--theta-i: at least one incident angle is needed");
    for (double t : o.theta_i_deg)
        if (!(t >= 0.0 && t < 90.0))
            throw std::invalid_argument("--theta-i: incident angles must be in [0, 90) degrees, got " +
                                        std::to_string(t));
    if (o.paths == 0) throw std::invalid_argument("--paths must be at least 1");
    if (o.paths > kMaxPathsPerAngle)
        throw std::invalid_argument("--paths: at most " + format_g9(double(kMaxPathsPerAngle)) +
                                    " paths per incident angle (the 64-bit energy book holds no more), got " +
                                    format_g9(double(o.paths)));
    if (!divides(o.dtheta_deg, 90.0))
        throw std::invalid_argument("--dtheta must divide 90 degrees into a whole number of bins");
    if (!divides(o.dphi_deg, 180.0))
        throw std::invalid_argument("--dphi must divide 180 degrees into a whole number of bins");
    if (o.max_events < 1) throw std::invalid_argument("--max-events must be at least 1");
    // lavapipe silently ends every loop of an invocation after 65535 iterations in total (docs/PHYSICS.md).
    if (uint64_t(o.paths_per_invocation) * (uint64_t(o.max_events) + 2) + o.paths_per_invocation + 8 >= 65535)
        throw std::invalid_argument("--max-events " + std::to_string(o.max_events) +
                                    " is too large: paths per invocation (" + std::to_string(o.paths_per_invocation) +
                                    ") x (max events + 2) must stay below 65535");
}

WalkStack walk_stack_for(const Stack& stack, const SimOptions& o) {
    return walk_stack(stack, o.specialised, o.series, o.orders, o.max_events);
}

void check_resumable(const SimResult& prev, const Stack& stack, const SimOptions& opt) {
    auto refuse = [](const std::string& what) {
        throw std::invalid_argument("--resume: the earlier run differs in " + what + "; it cannot be continued");
    };
    if (stack_to_toml(prev.stack) != stack_to_toml(stack)) refuse("its stack");
    if (prev.options.seed != opt.seed) refuse("--seed (" + std::to_string(prev.options.seed) + ")");
    if (prev.options.dtheta_deg != opt.dtheta_deg || prev.options.dphi_deg != opt.dphi_deg)
        refuse("its bins (--dtheta/--dphi)");
    if (prev.options.max_events != opt.max_events)
        refuse("--max-events (" + std::to_string(prev.options.max_events) + ")");
    if (prev.options.orders != opt.orders) refuse("--orders");
    if (prev.options.specialised != opt.specialised) refuse("--general-walk");
    if (prev.options.series != opt.series) refuse("--no-series");
    if (prev.options.baked_stack != opt.baked_stack) refuse("--no-baked-stack");
    if (prev.options.theta_i_deg != opt.theta_i_deg) refuse("its incident angles (--theta-i)");
    for (const AngleResult& a : prev.angles)
        if (a.paths > opt.paths)
            refuse("its path count: it already has " + std::to_string(a.paths) + " paths at theta_i " +
                   std::to_string(a.theta_i_deg) + ", more than --paths " + std::to_string(opt.paths));
}

}   // namespace gonio
