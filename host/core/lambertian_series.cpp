// lambertian_series.cpp: see lambertian_series.h.
#include "lambertian_series.h"
#include "quadrature.h"
#include "stack_gpu.h"
#include "interface.glsl"   // the top interface's sampling and Fresnel, as the walk has them

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <mutex>
#include <vector>

namespace gonio {

namespace {

glm::dvec3 exp_neg(const glm::vec3& tau, double inv_cos) {
    return {std::exp(-tau.x * inv_cos), std::exp(-tau.y * inv_cos), std::exp(-tau.z * inv_cos)};
}

bool is_coat_over_lambertian(const StackGpu& g) {
    return stack_layer_count(g.info) == 2 && layer_kind(g.layers[0]) == KIND_DIELECTRIC &&
           layer_kind(g.layers[1]) == KIND_LAMBERTIAN;
}

// Whether the coat's medium scatters: pack_stack gives a medium its scattering albedo only where it scatters
bool coat_scatters(const StackGpu& g) { return layer_scattering_albedo(g.layers[0]) != glm::vec3(0.0f); }

// A rule on [0, 1] whose nodes crowd both ends (the sigmoidal map x = v^3 / (v^3 + (1 - v)^3) of Gauss-Legendre
// nodes): an integrand with a square-root or kink singularity at an end (where total internal reflection sets in,
// or an exit direction crosses the horizon) is integrated to high order.
struct Rule {
    std::vector<double> x, w;
};
Rule sigmoidal_rule(int n) {
    Rule r;
    std::vector<double> v, wv;
    gauss_legendre_01(n, v, wv);
    for (int i = 0; i < n; ++i) {
        double a = v[i] * v[i] * v[i], b = (1 - v[i]) * (1 - v[i]) * (1 - v[i]);
        double da = 3 * v[i] * v[i], db = -3 * (1 - v[i]) * (1 - v[i]);
        r.x.push_back(a / (a + b));
        r.w.push_back(wv[i] * (da * b - a * db) / ((a + b) * (a + b)));
    }
    return r;
}

// Roots in [0, 1] of f, found by a scan of `scan` steps and bisection.
template <class Fn>
void roots01(const Fn& f, int scan, std::vector<double>& out) {
    double x0 = 0.0, f0 = f(0.0);
    for (int i = 1; i <= scan; ++i) {
        double x1 = double(i) / scan, f1 = f(x1);
        if ((f0 < 0) != (f1 < 0)) {
            double lo = x0, hi = x1, flo = f0;
            for (int it = 0; it < 30; ++it) {
                double mid = 0.5 * (lo + hi), fm = f(mid);
                if ((fm < 0) == (flo < 0)) {
                    lo = mid;
                    flo = fm;
                } else
                    hi = mid;
            }
            out.push_back(0.5 * (lo + hi));
        }
        x0 = x1;
        f0 = f1;
    }
}

// escaped RGB, returned RGB, lost RGB
using Terms = std::array<double, 9>;
Terms& operator+=(Terms& a, const Terms& b) {
    for (int i = 0; i < 9; ++i) a[i] += b[i];
    return a;
}

// The coat as a trip meets it from below (walk.glsl, `down` false): roughness, relative indices, optical depth.
struct CoatFromBelow {
    float alpha;
    float eta, inv_eta;   // from below: eta = n_above / n_coat, inv_eta = n_coat / n_above
    glm::vec3 tau;
    bool rough, matched;
    double c_crit;   // total internal reflection where the cosine to the microfacet normal is below c_crit
};
CoatFromBelow coat_from_below(const StackGpu& g) {
    const LayerGpu& L = g.layers[0];
    CoatFromBelow coat;
    coat.alpha = layer_alpha(L);
    coat.eta = layer_inv_eta(L);
    coat.inv_eta = layer_eta(L);
    coat.tau = layer_optical_depth(L);
    coat.rough = coat.alpha > 0.0f;
    coat.matched = std::fabs(coat.eta - 1.0f) < INDEX_MATCH_EPS;
    coat.c_crit = coat.eta < 1.0f ? std::sqrt(1.0 - double(coat.eta) * coat.eta) : -1.0;
    return coat;
}

// One visible normal m (u1, u2) met from below along wi, of quadrature weight wq: what the coat lets out (escaped),
// reflects back to the base (returned, through the coat's medium) and loses (reflected or refracted into shadow).
void visible_normal_event(const CoatFromBelow& coat, const vec3& wi, float u1, float u2, double wq, Terms& out) {
    if (coat.matched) {   // no interface (sample_dielectric_inv)
        for (int c = 0; c < kChannels; ++c) out[c] += wq;
        return;
    }
    const float alpha = coat.alpha, eta = coat.eta, inv_eta = coat.inv_eta;
    const bool rough = coat.rough;
    vec3 m = rough ? sample_ggx_visible_normal(wi, alpha, u1, u2) : vec3(0.0f, 0.0f, 1.0f);
    float cos_im = dot(wi, m), cos_t;
    const double F = fresnel_dielectric_cos_t(cos_im, eta, inv_eta * inv_eta, cos_t);
    const vec3 wr = reflect_about(wi, m);
    const vec3 wt = (cos_im * inv_eta - cos_t) * m - wi * inv_eta;
    const double gr = wr.z > 0.0f ? (rough ? ggx_G2_over_G1(wi, wr, alpha) : 1.0f) : 0.0;
    const double gt = F < 1.0 && wt.z < 0.0f ? (rough ? ggx_G2_over_G1(wi, wt, alpha) : 1.0f) : 0.0;
    const glm::dvec3 down =
        gr > 0.0 ? exp_neg(coat.tau, 1.0 / double(wr.z)) : glm::dvec3(0.0);   // Beer-Lambert to the base
    for (int c = 0; c < kChannels; ++c) {
        out[c] += wq * (1.0 - F) * gt;
        out[kChannels + c] += wq * F * gr * down[c];
        out[2 * kChannels + c] += wq * (F * (1.0 - gr) + (1.0 - F) * (1.0 - gt));
    }
}

// The panels of the visible normal's height u2 at azimuth u1, split where the integrand has kinks: total internal
// reflection sets in (cos_im = c_crit), the reflected or refracted direction crosses the horizon. Sorted, 0 and 1
// included.
std::vector<double> height_panel_edges(const CoatFromBelow& coat, const vec3& wi, float u1) {
    const float alpha = coat.alpha, eta = coat.eta, inv_eta = coat.inv_eta;
    auto m_of = [&](double u2) { return sample_ggx_visible_normal(wi, alpha, u1, float(u2)); };
    std::vector<double> b{0.0, 1.0};
    if (coat.c_crit > 0.0) roots01([&](double u2) { return double(dot(wi, m_of(u2))) - coat.c_crit; }, 12, b);
    roots01([&](double u2) { return double(reflect_about(wi, m_of(u2)).z); }, 12, b);
    roots01(
        [&](double u2) {
            vec3 m = m_of(u2);
            float ci = dot(wi, m), ct;
            fresnel_dielectric_cos_t(ci, eta, inv_eta * inv_eta, ct);
            return double(((ci * inv_eta - ct) * m - wi * inv_eta).z);
        },
        12, b);
    std::sort(b.begin(), b.end());
    return b;
}

// A rough coat's visible normals at azimuth u1d (one node of the midpoint rule), integrated over their height u2 by
// panels of the rule r2.
Terms over_normal_height(const CoatFromBelow& coat, const vec3& wi, double u1d, const Rule& r2) {
    Terms o{};
    const float u1 = float(u1d);
    const std::vector<double> b = height_panel_edges(coat, wi, u1);
    for (size_t k = 0; k + 1 < b.size(); ++k) {
        const double a0 = b[k], du = b[k + 1] - b[k];
        if (du > 0.0)
            for (size_t j = 0; j < r2.x.size(); ++j)
                visible_normal_event(coat, wi, u1, float(a0 + du * r2.x[j]), du * r2.w[j], o);
    }
    return o;
}

// Leaving the base upwards along s = sin^2 theta: what the coat lets out, returns and loses, through the coat's
// medium both ways. A rough coat's visible normals by n1 midpoints in azimuth u1, each integrated in height.
Terms leaving_base(const CoatFromBelow& coat, double s, const Rule& r2, int n1) {
    Terms out{};
    const double c = std::sqrt(1.0 - s);
    if (!(c > 0.0)) return out;
    // leaving the base upwards along d = (sin, 0, cos); at the coat from below, wi = (-d.x, -d.y, d.z)
    const vec3 wi(-float(std::sqrt(s)), 0.0f, float(c));
    if (!coat.rough) {
        visible_normal_event(coat, wi, 0.5f, 0.5f, 1.0, out);
    } else {
        for (int i1 = 0; i1 < n1; ++i1) out += over_normal_height(coat, wi, (i1 + 0.5) / n1, r2);
        for (double& v : out) v /= n1;
    }
    const glm::dvec3 a_up = exp_neg(coat.tau, 1.0 / c);
    for (int k = 0; k < 3; ++k)
        for (int ch = 0; ch < kChannels; ++ch) out[kChannels * k + ch] *= a_up[ch];
    return out;
}

// The panels in s = sin^2 theta (the cosine density is uniform in s), split where total internal reflection sets in
// and, for a rough coat, at distances alpha 2^k from that angle (the transition is as wide as the roughness).
std::vector<double> sin2_panel_edges(const CoatFromBelow& coat) {
    std::vector<double> edges{0.0, 1.0};
    const float eta = coat.eta;
    const double s_crit = eta < 1.0f ? double(eta) * eta : 1.0;
    if (!coat.matched && s_crit < 1.0) {
        edges.push_back(s_crit);
        if (coat.rough) {
            const double tc = std::asin(std::sqrt(s_crit));
            for (double d = 0.25 * coat.alpha; d < M_PI / 2; d *= 2.0)
                for (double sign : {-1.0, 1.0}) {
                    double t = tc + sign * d;
                    if (t > 0.0 && t < M_PI / 2) edges.push_back(std::sin(t) * std::sin(t));
                }
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end(), [](double a, double b) { return b - a < 1e-12; }), edges.end());
    return edges;
}

}   // namespace

namespace {
LambertianSeries compute_series(const StackGpu& g);
}

SeriesTrip lambertian_trip(const StackGpu& g, double refine) {
    if (!is_coat_over_lambertian(g))
        throw std::invalid_argument("lambertian_trip: needs a dielectric coat over a Lambertian base");
    const CoatFromBelow coat = coat_from_below(g);
    // node counts per panel in s, per panel in u2, and u1's midpoint rule; refine 1: within 4e-5 of a 4x finer rule
    // on the stacks tests/test_series.cpp checks (lambertian_series estimates the error from a coarser rule)
    const int ns = std::max(4, int(std::lround(16 * refine))), n2 = std::max(4, int(std::lround(24 * refine)));
    const Rule rs = sigmoidal_rule(ns), r2 = sigmoidal_rule(n2);
    const int n1 = std::max(8, int(std::lround(64 * refine)));

    const std::vector<double> edges = sin2_panel_edges(coat);
    Terms sum{};
    for (size_t p = 0; p + 1 < edges.size(); ++p) {
        const double s0 = edges[p], ds = edges[p + 1] - edges[p];
        for (size_t i = 0; i < rs.x.size(); ++i) {
            Terms v = leaving_base(coat, s0 + ds * rs.x[i], r2, n1);
            for (int k = 0; k < 9; ++k) sum[k] += ds * rs.w[i] * v[k];
        }
    }
    SeriesTrip t;
    t.escaped = {sum[0], sum[1], sum[2]};
    t.returned = {sum[3], sum[4], sum[5]};
    t.lost = {sum[6], sum[7], sum[8]};
    return t;
}

LambertianSeries lambertian_series(const StackGpu& g) {
    // memoised: what the series depends on is the coat (kind, eta, alpha, tau) and the base's albedo
    static std::mutex mutex;
    static std::map<std::vector<float>, LambertianSeries> memo;
    std::vector<float> key;
    if (is_coat_over_lambertian(g) && !coat_scatters(g)) {
        const LayerGpu& coat = g.layers[0];
        const glm::vec3 tau = layer_optical_depth(coat), albedo = layer_albedo(g.layers[1]);
        key = {layer_alpha(coat), layer_eta(coat), layer_inv_eta(coat), tau.x, tau.y, tau.z, albedo.x, albedo.y,
               albedo.z,          coat.c1.w};
        std::lock_guard<std::mutex> lock(mutex);
        auto it = memo.find(key);
        if (it != memo.end()) return it->second;
    }
    LambertianSeries r = compute_series(g);
    if (!key.empty()) {
        std::lock_guard<std::mutex> lock(mutex);
        memo.emplace(key, r);
    }
    return r;
}

namespace {
LambertianSeries compute_series(const StackGpu& g) {
    LambertianSeries r;
    if (!is_coat_over_lambertian(g)) {
        r.reason = "not a dielectric coat over a Lambertian base";
        return r;
    }
    if (coat_scatters(g)) {   // a trip then has no closed-form return: light scattered in the coat
        r.reason = "the coat's medium scatters (the series sums Beer-Lambert crossings only)";
        return r;
    }
    if (layer_alpha(g.layers[0]) > 0.0f && layer_microsurface(g.layers[0]) != 0u) {
        r.reason =
            "the coat's microsurface is not GGX with height-correlated Smith, single scattering (the quadrature "
            "of its trips is)";
        return r;
    }
    // the terms from a rule with 1.5 times the nodes in every dimension, and as their error estimate twice the
    // difference from the plain rule (which errs more)
    r.trip = lambertian_trip(g, 1.5);
    const SeriesTrip coarse = lambertian_trip(g, 1.0);
    const glm::dvec3 albedo(layer_albedo(g.layers[1]));
    double err = 0.0;
    for (int c = 0; c < kChannels; ++c)
        err =
            std::max({err, std::fabs(coarse.escaped[c] - r.trip.escaped[c]),
                      std::fabs(coarse.returned[c] - r.trip.returned[c]), std::fabs(coarse.lost[c] - r.trip.lost[c])});
    r.quadrature_error =
        2.0 * err;   // a safety factor of 2 (tests/test_series.cpp checks it against a 2.5x finer rule)
    err = r.quadrature_error;
    const glm::dvec3 kept = albedo * r.trip.returned;
    const double kept_max = std::max(kept.x, std::max(kept.y, kept.z));
    if (!(kept_max < 1.0)) {
        r.reason = "the coat returns all the light to a white base";
        return r;
    }
    r.gain = 1.0 / (1.0 - kept);
    r.lost_all = r.trip.lost * r.gain;
    // relative error of the diffuse exits escaped S from the quadrature's: d(escaped)/escaped + albedo S d(returned)
    for (int c = 0; c < kChannels; ++c)
        r.relative_error =
            std::max(r.relative_error, err / std::max(r.trip.escaped[c], 1e-2) + albedo[c] * r.gain[c] * err);
    if (r.relative_error > kMaxSeriesRelativeError) {
        r.reason = "the quadrature of its terms is not accurate enough here (estimated relative error " +
                   std::to_string(r.relative_error) + ")";
        return r;
    }

    // the emission cone: the coat's escape cone (total internal reflection beyond it), widened by 4 alpha for a
    // rough coat; with a smooth coat nothing leaves from outside it, so the cone alone is sampled
    const double eta = layer_inv_eta(g.layers[0]), alpha = layer_alpha(g.layers[0]);
    if (eta < 1.0 && std::fabs(eta - 1.0) >= INDEX_MATCH_EPS) {
        const double t = std::asin(eta) + (alpha > 0.0 ? std::atan(4.0 * alpha) : 0.0);
        const double s2 = t < M_PI / 2 ? std::sin(t) * std::sin(t) : 1.0;
        if (s2 < 0.95) {
            r.cone_sin2 = s2;
            r.cone_prob = alpha > 0.0 ? 0.75 : 1.0;
            r.factor_in = 1.0 / (r.cone_prob / s2 + 1.0 - r.cone_prob);
            r.factor_out = r.cone_prob < 1.0 ? 1.0 / (1.0 - r.cone_prob) : 0.0;
        }
    }
    const double gain_max = std::max(r.gain.x, std::max(r.gain.y, r.gain.z));
    r.max_weight = gain_max * std::max({r.factor_in, r.factor_out, 1.0});
    if (r.max_weight > kMaxSeriesWeight) {
        r.reason = "an exiting path could weigh " + std::to_string(r.max_weight) + " (more than " +
                   std::to_string(int(kMaxSeriesWeight)) + "): the coat traps nearly all the light";
        return r;
    }
    while (std::ldexp(1.0, r.weight_shift) < r.max_weight) ++r.weight_shift;
    r.applies = true;
    return r;
}

}   // namespace

}   // namespace gonio
