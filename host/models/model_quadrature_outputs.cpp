// model_quadrature_outputs.cpp: models.comp's push constants for the graded quadrature, and what its outputs say
// about a model's values (model_evaluator_impl.h).
#include "model_evaluator_impl.h"
#include "incidence.h"
#include "model_twin.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gonio {

void note_invalid(ModelSlices& ms, const QuadBin& q, uint32_t angle, uint32_t side, uint32_t bin) {
    if (q.bad > 0.0f) {
        ms.invalid_nodes += uint64_t(q.bad);
        ms.invalid_bins.push_back({angle, side, bin});
    }
    if (q.nodes < 0.0f) ms.cut_short_bins.push_back({angle, side, bin});
    // the same in every bin of a dispatch (l fixed): once per incident angle and side
    const uint32_t hints = uint32_t(q.hint_flags);
    auto once = [&](std::vector<ModelSlices::BinRef>& v) {
        if (v.empty() || v.back().angle != angle || v.back().side != side) v.push_back({angle, side, 0});
    };
    if (hints & QUAD_HINTS_UNUSABLE) once(ms.invalid_hints);
    if (hints & QUAD_HINTS_UNRESOLVED) once(ms.float_unresolved);
}

namespace {

// "theta_i A R; theta_i B T; ..." (the first three)
std::string where_angles(const std::vector<ModelSlices::BinRef>& v, const ModelGrid& grid) {
    std::string at;
    for (size_t i = 0; i < v.size() && i < 3; ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%stheta_i %g %s", i ? "; " : "", grid.theta_i_deg[v[i].angle],
                      v[i].side ? "T" : "R");
        at += buf;
    }
    if (v.size() > 3) at += "; ...";
    return at;
}

}   // namespace

std::string describe_invalid(const ModelSlices& ms, const ModelGrid& grid) {
    auto where = [&](const std::vector<ModelSlices::BinRef>& bins) {
        std::string w;
        for (size_t i = 0; i < bins.size() && i < 3; ++i) {
            const auto& r = bins[i];
            const uint32_t t = r.bin / grid.n_phi, p = r.bin % grid.n_phi;
            char buf[160];
            std::snprintf(buf, sizeof buf, "%stheta_i %g %s theta %g-%g phi %g", i ? "; " : "",
                          grid.theta_i_deg[r.angle], r.side ? "T" : "R", t * grid.dtheta_deg,
                          std::min(90.0, (t + 1) * grid.dtheta_deg), p * grid.dphi_deg);
            w += buf;
        }
        if (bins.size() > 3) w += "; ...";
        return w;
    };
    std::string why;
    if (ms.invalid_nodes > 0)
        why = std::to_string(ms.invalid_nodes) + " quadrature nodes in " + std::to_string(ms.invalid_bins.size()) +
              " bins where f is NaN, infinite or negative (" + where(ms.invalid_bins) + ")" +
              (ms.file.empty() ? "" : "; a model file's gonio_layer(i) is all NaN for a layer the stack does not have");
    if (!ms.invalid_hints.empty())
        why += (why.empty() ? "" : "; ") +
               std::string(
                   "model_lobes gave an unusable lobe (a NaN or infinite direction, a negative roughness, or "
                   "more than 8 lobes; ") +
               where_angles(ms.invalid_hints, grid) + ")";
    if (!ms.float_unresolved.empty())
        why += (why.empty() ? "" : "; ") +
               std::string(
                   "a black box cannot integrate a lobe narrower in v than float resolves (2 alpha cos theta "
                   "below 2e-5; ") +
               where_angles(ms.float_unresolved, grid) +
               "; its lobes: model_lobes, else the stack's narrowest interface): the built-in models put such lobes "
               "on visible-normal grids";
    if (!ms.cut_short_bins.empty())
        why += (why.empty() ? "" : "; ") + std::to_string(ms.cut_short_bins.size()) +
               " bins whose quadrature lavapipe's loop limiter cut short (its 65535 loop trips per invocation; " +
               where(ms.cut_short_bins) + ")";
    return why;
}

double ring_projected_omega(const ModelGrid& grid, uint32_t t) {
    const double lo = t * grid.dtheta_deg * M_PI / 180, hi = (t + 1) * grid.dtheta_deg * M_PI / 180;
    return 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * grid.dphi_deg * M_PI / 180;
}

ModelPush quadrature_push(uint32_t terms, const ModelGrid& grid, double theta, int side, const ModelStack& mstack,
                          double narrowest, bool coat_model, uint32_t max_rects, bool tables) {
    const Stack& s = mstack.stack;
    const double ti = theta * M_PI / 180;
    const double eta = s.layers[0].ior.x / s.exterior_ior;
    ModelPush pc{};
    pc.terms = terms;
    pc.n_theta = grid.n_theta;
    pc.n_phi = grid.n_phi;
    pc.dtheta = float(grid.dtheta_deg * M_PI / 180);
    pc.dphi = float(grid.dphi_deg * M_PI / 180);
    pc.sin_ti = float(std::sin(ti));
    pc.cos_ti = float(std::cos(ti));
    pc.grid = lobe_grid_nodes(theta);
    pc.side = uint32_t(side);
    pc.use_tables = tables ? 1u : 0u;
    pc.grid_rows = lobe_grid_nodes(theta);
    pc.w_theta = float(2.0 * narrowest);
    pc.a_phi = std::sin(ti) > 1e-6 ? float(narrowest) : 0.0f;
    pc.w_horizon = float(narrowest);
    // v beyond the critical angle of a coat of lower index (a denser exterior) cannot enter it: the base terms of
    // the two-layer models stop there
    pc.theta_break = coat_model && eta < 1.0 ? float(std::asin(eta)) : 0.0f;
    pc.max_rects = max_rects;
    pc.cos_kink = s.layers[0].kind == InterfaceKind::Dielectric && eta < 1.0 ? float(std::sqrt(1.0 - eta * eta)) : 0.0f;
    pc.mu_jump = float(mstack.mu_jump);
    // the lobe's width in the components of v, 2 alpha cos(theta_i), against 1e-4 (1700 float steps of 6e-8):
    // narrower lobes get up to 8x finer pieces at their peak (models.comp)
    pc.refine =
        narrowest > 0.0 ? float(std::clamp(1e-4 / (2.0 * narrowest * std::max(std::cos(ti), 1e-3)), 1.0, 8.0)) : 1.0f;
    pc.split = 1u;
    pc.bin_first = 0u;
    // the incident azimuth (models.comp to_surface_frame), as the walk has it (incidence.h), and in whole bins plus
    // a rest in [-dphi / 2, dphi / 2)
    const IncidentTrig it = incident_trig(theta, grid.phi_i_deg);
    pc.sin_pi = it.sin_pi;
    pc.cos_pi = it.cos_pi;
    const double bins = std::floor(grid.phi_i_deg / grid.dphi_deg + 0.5);
    pc.phi_shift = uint32_t(bins) % grid.n_phi;
    pc.phi_rest = float((grid.phi_i_deg - bins * grid.dphi_deg) * M_PI / 180);
    return pc;
}

}   // namespace gonio
