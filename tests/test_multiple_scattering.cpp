// The walk on a rough interface's microsurface (shaders/lib/microsurface_walk.glsl: Heitz et al. 2016), compiled as
// C++ through GLM, against what its code does not compute:
// - energy: a non-absorbing dielectric interface, from either side, alpha up to 1, GGX and Beckmann, theta_i to 89.9
//   degrees: every path leaves (R + T = 1) within 1e-4, with weight 1; a conductor with F = 1: albedo 1 within 1e-4;
// - the first meeting: the walk stopped after one meeting leaves with the single-scattering BSDF's density times the
//   height-correlated chance to leave, (1 + L_i) / (1 + L_i + L_o) reflected and (1 + L_i) B(1 + L_i, 1 + L_o)
//   refracted (Heitz 2014, "Understanding the masking-shadowing function", Sec. 6: the heights' Beta integral),
//   chi-square against the densities of interface.glsl's single-scattering samplers (themselves held by
//   test_sampling.cpp) and the Beta function of the C library;
// - the visible normals below the horizon, which the walk samples after a path going up meets the microsurface
//   again: chi-square against max(0, wi.m) D(m) / (the projected area by quadrature);
// - reciprocity of the reflection, bin by bin: with directions of incidence drawn by cos theta, the weight that goes
//   from bin a to bin b and from b to a are equal in expectation (chi-square over the pairs).
#include "chi2.h"
#include "microfacet_quadrature.h"
#include "compat.glsl"
#include "rng.glsl"
#include "interface.glsl"
#include "microsurface_walk.glsl"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

glm::vec3 dir_from_theta(double deg) {
    const double t = deg * M_PI / 180.0;
    return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

Rng path_rng(uint32_t case_id, int i) { return rng_init(uint32_t(i), 0u, 9001u + case_id, 13u); }

// One interface of the tests: its microsurface and what it is
struct Interface {
    float alpha;
    uint micro;   // MICROSURFACE_BECKMANN or 0 (GGX)
    bool dielectric;
    float eta;   // dielectric: n_t / n_i
    vec3 c_eta, c_k;   // conductor
    std::string name() const {
        char b[160];
        std::snprintf(b, sizeof b, "%s %s alpha %.2f eta %.3f", microsurface_beckmann(micro) ? "Beckmann" : "GGX",
                      dielectric ? "dielectric" : "conductor", alpha, dielectric ? eta : c_eta.x);
        return b;
    }
};

// The i-th path of case case_id from wi, stopped after max_meetings meetings, as the walk draws it (the event's
// numbers, its own stream).
Scatter walk_path(const Interface& f, vec3 wi, uint32_t case_id, int i, uint max_meetings = MICROSURFACE_MAX_MEETINGS) {
    Rng r = path_rng(case_id, i);
    vec4 u = rng_peek4(r);
    return sample_microsurface_walk(wi, f.alpha, f.micro, f.dielectric, f.eta, 1.0f / f.eta, f.c_eta, f.c_k, u,
                                    microsurface_stream(r), max_meetings);
}

double lambda(vec3 w, const Interface& f) { return double(microsurface_lambda(w, f.alpha, f.micro)); }

double beta_function(double a, double b) { return std::exp(std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b)); }

TEST(MultipleScattering, DielectricLetsEveryPathLeave) {
    int cases = 0;
    double worst_kept = 0;
    for (uint micro : {0u, MICROSURFACE_BECKMANN})
        for (float eta : {1.5f, 1.0f / 1.5f})
            for (float alpha : {0.1f, 0.3f, 0.6f, 1.0f})
                for (double theta : {0.0, 30.0, 60.0, 75.0, 89.9}) {
                    const Interface f{alpha, micro, true, eta, vec3(0.0f), vec3(0.0f)};
                    const vec3 wi = dir_from_theta(theta);
                    const int n = 50000;
                    int left = 0, up = 0;
                    for (int i = 0; i < n; ++i) {
                        Scatter s = walk_path(f, wi, uint32_t(cases), i);
                        ASSERT_TRUE(std::isfinite(s.wo.x) && std::isfinite(s.wo.y) && std::isfinite(s.wo.z))
                            << f.name() << " theta " << theta << " path " << i;
                        ASSERT_NEAR(glm::length(s.wo), 1.0f, 1e-4f) << f.name() << " theta " << theta;
                        ASSERT_EQ(s.weight, vec3(1.0f)) << f.name();
                        ASSERT_EQ(s.absorbed, vec3(0.0f)) << f.name();
                        left += s.valid ? 1 : 0;
                        up += s.valid && s.wo.z > 0.0f ? 1 : 0;
                    }
                    // R + T: every path that leaves carries weight 1
                    const double kept = 1.0 - double(left) / n;
                    worst_kept = std::max(worst_kept, kept);
                    EXPECT_LE(kept, 1e-4)
                        << f.name() << " theta " << theta << ": R " << double(up) / n << " T " << double(left - up) / n;
                    ++cases;
                }
    std::printf("%d dielectric interfaces: the most paths still on a microsurface after %u meetings %.2g\n", cases,
                MICROSURFACE_MAX_MEETINGS, worst_kept);
}

TEST(MultipleScattering, ConductorWithFOfOneReflectsEverything) {
    uint32_t id = 100;
    for (uint micro : {0u, MICROSURFACE_BECKMANN})
        for (float alpha : {0.1f, 0.3f, 0.6f, 1.0f})
            for (double theta : {0.0, 45.0, 75.0, 89.9}) {
                // n = 1, k = 1e4: 1 - F below 4e-8 on every facet
                const Interface f{alpha, micro, false, 1.0f, vec3(1.0f), vec3(1e4f)};
                const vec3 wi = dir_from_theta(theta);
                const int n = 50000;
                double albedo = 0;
                for (int i = 0; i < n; ++i) {
                    Scatter s = walk_path(f, wi, id, i);
                    ASSERT_TRUE(std::isfinite(s.wo.x) && std::isfinite(s.wo.y) && std::isfinite(s.wo.z));
                    if (s.valid) {
                        EXPECT_GT(s.wo.z, 0.0f) << f.name() << ": a conductor reflects";
                        albedo += s.weight.y;
                    }
                    EXPECT_NEAR(double(s.weight.y + s.absorbed.y), 1.0, 1e-6) << f.name() << ": absorbed 1 - weight";
                }
                EXPECT_NEAR(albedo / n, 1.0, 1e-4) << f.name() << " theta " << theta;
                ++id;
            }
}

// The integral over the sphere of q(w), midpoint rule in (theta, phi): a lobe on a pole (a refracted lobe at normal
// incidence, a few degrees wide) is resolved by theta's steps, which cos theta's would not
template <class Q>
double over_sphere(Q q, int n_theta = 1800, int n_phi = 240) {
    double s = 0;
    for (int i = 0; i < n_theta; ++i) {
        const double t = (i + 0.5) * M_PI / n_theta;
        double ring = 0;
        for (int j = 0; j < n_phi; ++j) {
            const double p = (j + 0.5) * 2 * M_PI / n_phi;
            ring +=
                q(glm::vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t))));
        }
        s += ring * std::sin(t);
    }
    return s * (M_PI / n_theta) * (2 * M_PI / n_phi);
}

// The density of the direction of a path that leaves after its first meeting (a sub-density: the rest meets the
// microsurface again): the single-scattering BSDF's lobe on wo's side, as sampled from the visible normals (Walter et
// al. 2007, eqs. 14 and 17, with D_wi for D |m.n|), times the chance to leave: reflected (1 + L_i) / (1 + L_i + L_o),
// refracted (1 + L_i) B(1 + L_i, 1 + L_o). F of the dielectric on the facet; a conductor reflects everything it does
// not absorb, so its directions have no F (the walk weighs them by it).
double first_meeting_density(const Interface& f, vec3 wi, vec3 wo) {
    const double li = lambda(wi, f), lo = lambda(wo, f);
    if (wo.z > 0.0f) {   // reflected: m = the half vector
        const vec3 m = glm::normalize(wi + wo);
        const double cos_im = glm::dot(wi, m);
        if (cos_im <= 0 || m.z <= 0) return 0.0;
        const double F = f.dielectric ? double(fresnel_dielectric(float(cos_im), f.eta)) : 1.0;
        return F * double(visible_normal_pdf(wi, m, f.alpha, f.micro)) / (4 * cos_im) * (1 + li) / (1 + li + lo);
    }
    if (!f.dielectric) return 0.0;
    vec3 m = -glm::normalize(wi + f.eta * wo);   // refracted: the generalised half vector
    if (m.z < 0.0f) m = -m;
    const double ci = glm::dot(wi, m), co = glm::dot(wo, m);
    if (ci <= 0 || co >= 0) return 0.0;
    const double den = ci + f.eta * co;
    const double p = (1 - fresnel_dielectric(float(ci), f.eta)) * visible_normal_pdf(wi, m, f.alpha, f.micro) * f.eta *
                     f.eta * std::fabs(co) / (den * den);
    return p * (1 + li) * beta_function(1 + li, 1 + lo);
}

TEST(MultipleScattering, FirstMeetingIsSingleScatteringWithHeightCorrelatedShadowing) {
    std::vector<std::pair<Interface, double>> cases;
    for (uint micro : {0u, MICROSURFACE_BECKMANN})
        for (float alpha : {0.3f, 1.0f})
            for (double theta : {0.0, 45.0, 75.0}) {
                cases.push_back({{alpha, micro, false, 1.0f, vec3(0.2f), vec3(3.0f)}, theta});
                for (float eta : {1.5f, 1.0f / 1.5f}) cases.push_back({{alpha, micro, true, eta, vec3(0.0f)}, theta});
            }
    const double level = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(cases.size()));   // Sidak
    uint32_t id = 300;
    for (const auto& [f, theta] : cases) {
        const vec3 wi = dir_from_theta(theta);
        auto q = [&](glm::vec3 wo) { return first_meeting_density(f, wi, wo); };
        const double leaves = over_sphere(q);
        // a path that meets the microsurface again is moved to a uniform direction: the density q + (1 - Q) / 4 pi
        const uint32_t cid = id++;
        chi2::Result r = chi2::test(
            [&](int i) {
                Scatter s = walk_path(f, wi, cid, i, 1u);
                if (s.valid) return s.wo;
                Rng e = rng_init(uint32_t(i), 1u, 4242u + cid, 17u);
                vec4 u = rng_next4(e);
                const float z = 1.0f - 2.0f * u.x, rr = std::sqrt(std::max(0.0f, 1.0f - z * z));
                return glm::vec3(rr * std::cos(2 * float(M_PI) * u.y), rr * std::sin(2 * float(M_PI) * u.y), z);
            },
            [&](glm::vec3 wo) { return q(wo) + (1.0 - leaves) / (4 * M_PI); }, 200000, 40, 80,
            f.dielectric && theta == 0.0 ? 96 : 24);   // the refracted lobe on the pole: a finer quadrature
        EXPECT_TRUE(r.failure.empty()) << r.failure;
        EXPECT_GT(r.p_value, level) << f.name() << " theta " << theta << ": chi2 " << r.chi2 << " dof " << r.dof;
        std::printf("first meeting, %s theta %g: leaves %.4f, chi2/dof %.3f p %.3g\n", f.name().c_str(), theta, leaves,
                    r.chi2 / std::max(1, r.dof), r.p_value);
    }
}

// The density of the visible normals of wi (either side of the horizon): max(0, wi.m) D(m) / A, A by quadrature
TEST(MultipleScattering, VisibleNormalsBelowTheHorizon) {
    struct C {
        uint micro;
        float alpha;
        double theta;
    };
    // below the horizon as far as the meetings are likely: |cot theta| / alpha up to 2.3 (a path going up steeper
    // than that meets the microsurface again with a chance below 1e-4)
    std::vector<C> cases{{0u, 0.3f, 100.0},
                         {0u, 0.3f, 115.0},
                         {0u, 1.0f, 120.0},
                         {0u, 1.0f, 155.0},
                         {MICROSURFACE_BECKMANN, 0.3f, 100.0},
                         {MICROSURFACE_BECKMANN, 0.3f, 115.0},
                         {MICROSURFACE_BECKMANN, 1.0f, 120.0},
                         {MICROSURFACE_BECKMANN, 1.0f, 155.0}};
    const double level = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(cases.size()));
    uint32_t id = 600;
    for (const C& c : cases) {
        const vec3 wi = dir_from_theta(c.theta);
        auto D = [&](vec3 m, float a) { return microsurface_beckmann(c.micro) ? beckmann_D(m, a) : ggx_D(m, a); };
        const double area = microfacet_quadrature::over_microfacets(
            c.alpha, D, [&](vec3 m) { return std::max(0.0, double(glm::dot(wi, m))); });
        const uint32_t cid = id++;
        chi2::Result r = chi2::test(
            [&](int i) {
                Rng e = path_rng(cid, i);
                vec4 u = rng_next4(e);
                return sample_visible_normal(wi, c.alpha, c.micro, u.x, u.y);
            },
            [&](glm::vec3 m) { return std::max(0.0, double(glm::dot(wi, m))) * D(m, c.alpha) / area; }, 400000, 40, 80,
            32);
        EXPECT_TRUE(r.failure.empty()) << r.failure;
        EXPECT_NEAR(r.pdf_integral, 1.0, 5e-3);
        EXPECT_GT(r.p_value, level) << (c.micro ? "Beckmann" : "GGX") << " alpha " << c.alpha << " theta " << c.theta
                                    << ": chi2 " << r.chi2 << " dof " << r.dof;
        std::printf("visible normals from below: %s alpha %.1f theta %g: projected area %.4f chi2/dof %.3f p %.3g\n",
                    c.micro ? "Beckmann" : "GGX", c.alpha, c.theta, area, r.chi2 / std::max(1, r.dof), r.p_value);
    }
}

// Reflection bins (theta of wi, theta of wo, |phi_o - phi_i|): 9 rings equal in projected solid angle, 6 azimuths
constexpr int kRings = 9, kAzimuths = 6;
int reflection_bin(vec3 w) {
    const double s2 = std::min(0.999999, double(w.x * w.x + w.y * w.y));
    return std::min(kRings - 1, int(s2 * kRings));
}

// chi-square of M(a, b) - M(b, a) over the pairs a < b, with directions of incidence drawn by cos theta (then each
// bin pair's expectation is the integral of f cos cos over it, symmetric where f is). `bias` multiplies each weight
// by 1 + bias wo.z: a negative control.
chi2::Result reciprocity(const Interface& f, uint32_t cid, int n, double bias = 0.0) {
    const int cells = kRings * kRings * kAzimuths;
    std::vector<double> s1(cells, 0), s2(cells, 0);
    for (int i = 0; i < n; ++i) {
        Rng e = rng_init(uint32_t(i), 2u, 777u + cid, 19u);
        vec4 u = rng_next4(e);
        const vec3 wi = sample_cosine_hemisphere(u.x, u.y);
        Scatter s = walk_path(f, wi, cid, i);
        if (!s.valid || s.wo.z <= 0.0f) continue;
        const double w = double(s.weight.y) * (1 + bias * s.wo.z);
        double dphi = std::fabs(std::atan2(s.wo.y, s.wo.x) - std::atan2(wi.y, wi.x));
        if (dphi > M_PI) dphi = 2 * M_PI - dphi;
        const int a = std::min(kAzimuths - 1, int(dphi / M_PI * kAzimuths));
        const int k = (reflection_bin(wi) * kRings + reflection_bin(s.wo)) * kAzimuths + a;
        s1[size_t(k)] += w;
        s2[size_t(k)] += w * w;
    }
    chi2::Result r;
    for (int ti = 0; ti < kRings; ++ti)
        for (int to = ti + 1; to < kRings; ++to)
            for (int a = 0; a < kAzimuths; ++a) {
                const size_t ab = size_t((ti * kRings + to) * kAzimuths + a),
                             ba = size_t((to * kRings + ti) * kAzimuths + a);
                const double var = s2[ab] + s2[ba];
                if (var <= 0) continue;
                r.chi2 += (s1[ab] - s1[ba]) * (s1[ab] - s1[ba]) / var;
                r.dof++;
            }
    r.p_value = r.dof > 0 ? chi2::gamma_q(0.5 * r.dof, 0.5 * r.chi2) : 0.0;
    return r;
}

TEST(MultipleScattering, ReflectionIsReciprocal) {
    std::vector<Interface> cases;
    for (uint micro : {0u, MICROSURFACE_BECKMANN})
        for (float alpha : {0.3f, 1.0f}) {
            cases.push_back({alpha, micro, false, 1.0f, vec3(0.2f), vec3(3.0f)});
            for (float eta : {1.5f, 1.0f / 1.5f}) cases.push_back({alpha, micro, true, eta, vec3(0.0f)});
        }
    const double level = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(cases.size()));
    uint32_t id = 800;
    for (const Interface& f : cases) {
        chi2::Result r = reciprocity(f, id++, 1000000);
        EXPECT_GT(r.p_value, level) << f.name() << ": chi2 " << r.chi2 << " dof " << r.dof;
        std::printf("reciprocity, %s: chi2/dof %.3f (dof %d) p %.3g\n", f.name().c_str(), r.chi2 / std::max(1, r.dof),
                    r.dof, r.p_value);
    }
    // the test can fail: weights 10% heavier towards the normal than at the horizon
    chi2::Result wrong = reciprocity(cases[0], 999u, 1000000, 0.1);
    EXPECT_LT(wrong.p_value, 1e-6) << "chi2 " << wrong.chi2 << " dof " << wrong.dof;
}

}   // namespace
