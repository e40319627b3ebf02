#include "model_plan.h"
#include "model_cpu.h"
#include "model_registry.h"
#include "model_stack.h"
#include "model_twin.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

GridShape lobe_grids(double theta_i_deg, uint32_t n_phi) {
    if (theta_i_deg == 0.0) {
        uint32_t cols = 2 * n_phi * uint32_t(std::ceil(180.0 / n_phi));
        return {cols, 256u, cols, 128u};
    }
    uint32_t g = lobe_grid_nodes(theta_i_deg);
    return {g, g, g / 2, g / 2};
}

PlanKind plan_kind(uint32_t code) { return model_registry().at(code).header.plan; }

PlanKind plan_kind_of(const std::string& id) {
    for (const ModelInfo& m : model_registry())
        if (m.id == id) return m.header.plan;
    return PlanKind::BlackBox;
}

uint32_t quadrature_max_rects(size_t model, const Stack& s) {
    const PlanKind kind = plan_kind(uint32_t(model));
    if (kind == PlanKind::Coat || kind == PlanKind::CoatRefracted) return 60000u / (40u + 25u * 1u);
    return quadrature_max_rects_black_box(s);   // Belcour's and tm21 loop over the stack's lobes
}

uint32_t quadrature_max_rects_black_box(const Stack& s) {
    const uint32_t trips = uint32_t(s.layers.size()) + 1;
    return 60000u / (40u + 25u * trips);
}

double mu_jump_of(const StackGpu& sg) {
    double P = 1.0, pmin = 1.0;
    for (uint32_t i = 0; i < stack_layer_count(sg.info); ++i) {
        const LayerGpu& L = sg.layers[i];
        if (layer_kind(L) != KIND_DIELECTRIC) break;
        P *= layer_eta(L);
        pmin = std::min(pmin, P);
    }
    return pmin < 1.0 ? std::sqrt(1.0 - pmin * pmin) : 0.0;
}

std::vector<TermPlan> plan(size_t model, const ModelStack& ms, double theta_deg, int side, bool tables,
                           uint32_t convention) {
    const Stack& s = ms.stack;
    std::vector<TermPlan> out;
    const PlanKind kind = plan_kind(uint32_t(model));
    const double ti = theta_deg * M_PI / 180;
    // a GGX lobe of roughness alpha about the mirror direction of l (grid_eta = 0), or about the mirror direction
    // of l refracted into a coat of relative IOR grid_eta: a delta on a lobe grid (drawn in the coat's directions
    // for a refracted one), else the graded quadrature
    auto lobe_term = [&](uint32_t term, double alpha, bool delta, double grid_eta = 0.0) {
        if (delta) {
            out.push_back({term, double(MODEL_MIN_ALPHA), true, 0.0, grid_eta});
            return;
        }
        const double a = std::max(alpha, double(MODEL_MIN_ALPHA));
        // the polar angle of the direction the lobe mirrors: l, or l refracted into the coat
        double theta_eff = ti;
        if (grid_eta > 0.0) {
            double st = std::sin(ti) / grid_eta;
            theta_eff = st < 1.0 ? std::asin(st) : M_PI / 2;
        }
        if (2.0 * a * std::cos(theta_eff) < kFloatUnresolved) {
            // too narrow for v's floats (kFloatUnresolved): visible-normal grids, drawn in the half vector
            out.push_back({term, a, false, 0.0, grid_eta});
            return;
        }
        // a lobe at Snell-refracted directions inside a coat of relative IOR eta is, seen from outside, eta times
        // wider than its roughness when eta > 1, narrower when eta < 1 (grading finer than needed costs nodes only)
        out.push_back({term, 0.0, false, a * (grid_eta > 0.0 ? std::min(1.0, grid_eta) : 1.0), 0.0});
    };
    if (kind == PlanKind::BlackBox)
        throw std::logic_error("plan: model " + code_id(uint32_t(model)) + " has no plan (a black box)");
    if (kind == PlanKind::Lobes || kind == PlanKind::LobesSymmetric) {
        // the model's own lobes (its file's GONIO_MODEL_LOBES) at this incident angle (the symmetric variant's table
        // is close to them near the peak), with the tables the device uses: which lobes exist and which are deltas is
        // decided on them
        auto lobes = [&](double mu) {
            return model_lobes_cpu(uint32_t(model), ms.gpu, mu, tables ? ms.tables.data() : nullptr, convention);
        };
        BelcourLobesHost b = lobes(std::cos(ti));
        if (side == 1) {
            if (b.e_t.x + b.e_t.y + b.e_t.z > 0.0) lobe_term(TERM_BASE, b.alpha_t, b.alpha_t < kModelDeltaAlpha);
            return out;
        }
        lobe_term(TERM_TOP, s.layers[0].roughness, s.layers[0].roughness == 0.0f);
        double lo = 1.0, hi = 0.0;
        auto take = [&](const BelcourLobesHost& lb) {
            for (size_t k = 1; k < lb.e.size(); ++k) {
                if (!(lb.e[k].x + lb.e[k].y + lb.e[k].z > 0.0)) continue;
                lo = std::min(lo, lb.alpha[k]);
                hi = std::max(hi, lb.alpha[k]);
            }
        };
        take(b);
        // the symmetric variant's lobes follow mu = |h.l|, not cos(theta_i) (which they equal at the mirror
        // direction, h = n): lobes below can exist for some v even when the forward lobes at l have none (light from
        // a dense medium beyond the critical angle: h.l > cos of it only for v towards l); then its base term is
        // planned from the lobes over the whole range of mu
        if (kind == PlanKind::LobesSymmetric && hi < lo)
            for (int i = 1; i <= 8; ++i) take(lobes(i / 8.0));
        if (hi >= lo) lobe_term(TERM_BASE, lo, hi < kModelDeltaAlpha);   // a delta only if every lobe below is one
        return out;
    }
    const double a0 = s.layers[0].roughness, a1 = s.layers[1].roughness;
    const double eta = s.layers[0].ior.x / s.exterior_ior;
    lobe_term(TERM_TOP, a0, a0 == 0.0);
    if (s.layers[1].kind == InterfaceKind::Lambertian) {
        out.push_back({TERM_BASE, 0.0, false, 0.0, 0.0});
        return out;
    }
    const bool unrefracted = kind == PlanKind::Coat;   // base at (l, v), own roughness
    if (s.layers.size() == 3 && s.layers[1].kind == InterfaceKind::Dielectric) {
        // a dielectric base (the coat, a dielectric interface, a Lambertian): the interface's lobe at (l, v) with the
        // roughness the model gives it (as a conductor base's, below), and the diffuse under it, broad
        if (!unrefracted)
            throw std::logic_error("plan: model " + code_id(uint32_t(model)) +
                                   " takes a dielectric base only with plan: coat (its base at the unrefracted l, v)");
        const double a = model_base_alpha_cpu(uint32_t(model), ms.gpu, convention);
        const bool delta = a1 == 0.0 && a <= double(MODEL_MIN_ALPHA);
        lobe_term(TERM_BASE, delta ? 0.0 : a, delta);
        out.push_back({TERM_DIFFUSE, 0.0, false, 0.0, 0.0});
        return out;
    }
    if (unrefracted) {
        // the roughness the model evaluates its base at: its own, or as the model's coat roughens it (its file's
        // GONIO_MODEL_BASE_ALPHA); a delta only where the model keeps a smooth base one
        const double a = model_base_alpha_cpu(uint32_t(model), ms.gpu, convention);
        const bool delta = a1 == 0.0 && a <= double(MODEL_MIN_ALPHA);
        lobe_term(TERM_BASE, delta ? 0.0 : a, delta);
    } else {
        // the base lobe at Snell-refracted (l1, v1): its grid is drawn about the mirror direction of l1 inside the
        // coat and refracted out (models.comp), where a lobe of the base's roughness is a GGX lobe; seen from
        // outside it is ~eta times wider (quadrature nodes)
        const double base_alpha = std::max(a0, a1);
        if (eta > std::sin(ti)) lobe_term(TERM_BASE, base_alpha, base_alpha == 0.0, eta);
        // else: l is totally reflected at the coat, no base term
    }
    return out;
}

}   // namespace gonio
