// sim_options.cpp: see sim_options.h.
#include "sim_options.h"
#include "reference.h"
#include "text_format.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gonio {

bool bin_width_divides(double w, double range) {
    const double n = range / w;
    return w > 0 && std::fabs(n - std::round(n)) < 1e-9 && n >= 1;
}

void require_plane_of_incidence(const SimOptions& opt, const std::string& what) {
    if (opt.phi_i_deg != 0.0)
        throw std::invalid_argument("this reference is at phi_i " + format_g9(opt.phi_i_deg) + " (simulate --phi-i); " +
                                    what + " take the plane of incidence, phi_i = 0, only");
}

void validate_options(const SimOptions& o) {
    const auto divides = bin_width_divides;
    if (o.theta_i_deg.empty()) throw std::invalid_argument("--theta-i: at least one incident angle is needed");
    for (double t : o.theta_i_deg)
        if (!(t >= 0.0 && t < 90.0))
            throw std::invalid_argument("--theta-i: incident angles must be in [0, 90) degrees, got " +
                                        std::to_string(t));
    if (o.theta_i_deg.size() > kMaxIncidentAngles)
        throw std::invalid_argument("--theta-i: at most " + std::to_string(kMaxIncidentAngles) +
                                    " incident angles in a run, got " + std::to_string(o.theta_i_deg.size()));
    if (!(o.phi_i_deg >= 0.0 && o.phi_i_deg < 360.0))
        throw std::invalid_argument("--phi-i: the incident azimuth must be in [0, 360) degrees, got " +
                                    format_g9(o.phi_i_deg));
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
    // the histograms the host keeps, checked before anything is allocated: angles x classes x 2 sides x bins x 6
    // sums of 8 bytes (an opaque stack has one side: half of it)
    const double bins = std::round(90.0 / o.dtheta_deg) * std::round(360.0 / o.dphi_deg);
    const double bytes = double(o.theta_i_deg.size()) * (o.orders ? 3 : 1) * 2 * bins * 6 * 8;
    if (bytes > double(kMaxHistogramBytes))
        throw std::invalid_argument("the run's histograms would take up to " + format_g9(bytes / (1u << 30)) +
                                    " GiB (" + std::to_string(o.theta_i_deg.size()) + " angles x " + format_g9(bins) +
                                    " bins" + (o.orders ? " x 3 classes" : "") + " x 2 sides x 48 bytes); at most " +
                                    std::to_string(kMaxHistogramBytes >> 30) +
                                    " GiB: fewer angles (--theta-i) or wider bins (--dtheta, --dphi)");
    // lavapipe silently ends every loop of an invocation after 65535 iterations in total (docs/PHYSICS.md).
    if (uint64_t(o.paths_per_invocation) * (uint64_t(o.max_events) + 2) + o.paths_per_invocation + 8 >= 65535)
        throw std::invalid_argument("--max-events " + std::to_string(o.max_events) +
                                    " is too large: paths per invocation (" + std::to_string(o.paths_per_invocation) +
                                    ") x (max events + 2) must stay below 65535");
}

WalkStack walk_stack_for(const Stack& stack, const SimOptions& o) {
    return walk_stack(stack, o.specialised, o.series, o.orders, o.max_events, o.branching);
}

namespace {

std::string angles_text(const std::vector<double>& t) {
    std::string s;
    for (double a : t) s += (s.empty() ? "" : ",") + format_g9(a);
    return s;
}
std::string on_off(bool given) { return given ? "given" : "not given"; }
std::string booking_text(bool entry_branch, uint32_t exit_estimates) {
    return std::string(entry_branch ? "the entry's both branches and " : "") + std::to_string(exit_estimates) +
           (exit_estimates == 1 ? " exit estimate" : " exit estimates") + " per path";
}

}   // namespace

void check_resumable(const SimResult& prev, const Stack& stack, const SimOptions& opt) {
    // what differs: the option, this run's value and the earlier run's
    auto refuse_if = [](bool differs, const std::string& option, const std::string& now, const std::string& before) {
        if (differs)
            throw std::invalid_argument(
                "--resume: " + option + " " + now + " differs from the earlier run's " + before +
                "; it cannot be continued (leave the option out to continue with the earlier " + "run's)");
    };
    if (stack_to_toml(prev.stack) != stack_to_toml(stack))
        throw std::invalid_argument(
            "--resume: the stack differs from the one the earlier run traced; it cannot be "
            "continued");
    const SimOptions& p = prev.options;
    refuse_if(p.seed != opt.seed, "--seed", std::to_string(opt.seed), std::to_string(p.seed));
    refuse_if(p.dtheta_deg != opt.dtheta_deg, "--dtheta", format_g9(opt.dtheta_deg), format_g9(p.dtheta_deg));
    refuse_if(p.dphi_deg != opt.dphi_deg, "--dphi", format_g9(opt.dphi_deg), format_g9(p.dphi_deg));
    refuse_if(p.max_events != opt.max_events, "--max-events", std::to_string(opt.max_events),
              std::to_string(p.max_events));
    refuse_if(p.orders != opt.orders, "--orders", on_off(opt.orders), on_off(p.orders));
    refuse_if(p.specialised != opt.specialised, "--general-walk", on_off(!opt.specialised), on_off(!p.specialised));
    refuse_if(p.series != opt.series, "--no-series", on_off(!opt.series), on_off(!p.series));
    refuse_if(p.branching != opt.branching, "--no-branching", on_off(!opt.branching), on_off(!p.branching));
    // a run of another gonio build may have booked with other estimators (docs/PHYSICS.md, "Booking estimators")
    const WalkSpec ws = walk_spec(stack, opt.specialised, opt.series, opt.orders, opt.max_events, opt.branching);
    if (prev.walk.entry_branch != ws.entry_branch || prev.walk.exit_estimates != ws.exit_estimates)
        throw std::invalid_argument("--resume: the earlier run booked with " +
                                    booking_text(prev.walk.entry_branch, prev.walk.exit_estimates) +
                                    ", this gonio with " + booking_text(ws.entry_branch, ws.exit_estimates) +
                                    "; it cannot be continued (an earlier version's run)");
    refuse_if(p.baked_stack != opt.baked_stack, "--no-baked-stack", on_off(!opt.baked_stack), on_off(!p.baked_stack));
    refuse_if(p.theta_i_deg != opt.theta_i_deg, "--theta-i", angles_text(opt.theta_i_deg), angles_text(p.theta_i_deg));
    refuse_if(p.phi_i_deg != opt.phi_i_deg, "--phi-i", format_g9(opt.phi_i_deg), format_g9(p.phi_i_deg));
    for (const AngleResult& a : prev.angles)
        if (a.paths > opt.paths)
            throw std::invalid_argument("--resume: the earlier run already has " + std::to_string(a.paths) +
                                        " paths at theta_i " + format_g9(a.theta_i_deg) + ", more than --paths " +
                                        std::to_string(opt.paths) + "; it cannot be continued");
}

}   // namespace gonio
