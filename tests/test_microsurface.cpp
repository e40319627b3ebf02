// The Beckmann microsurface (shaders/lib/beckmann.glsl, erf.glsl) against what its code does not compute: the error
// functions against the C library's double-precision ones; D's normalisation and the closed-form Smith Lambda against
// the projected area of the microsurface by quadrature (Heitz 2014, eq. 17: (1 + Lambda(w)) cos theta = the integral
// of max(0, w.m) D(m)); the visible-normal sampler against its density (chi-square); and the single-scattering
// albedo with F = 1, height-correlated and separable, sampled as the walk samples against the BRDF's integral.
#include "chi2.h"
#include "microfacet_quadrature.h"
#include "compat.glsl"
#include "rng.glsl"
#include "beckmann.glsl"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

glm::vec3 dir_from_theta(double deg) {
    const double t = deg * M_PI / 180.0;
    return glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

vec4 uniform4(uint32_t case_id, int i) {
    Rng r = rng_init(uint32_t(i), 0u, 777u + case_id, 3u);
    return rng_next4(r);
}

// The integral of g(m) D(m) over the Beckmann microfacets (microfacet_quadrature.h), on n_s x n_phi nodes.
template <class G>
double over_microfacets(double alpha, G g, int n_s = 3000, int n_phi = 720) {
    return microfacet_quadrature::over_microfacets(
        alpha, [](vec3 m, float a) { return beckmann_D(m, a); }, g, n_s, n_phi);
}

TEST(Microsurface, ErrorFunctionsAgainstTheCLibrary) {
    // erfc's relative error grows as x^2 in floats: exp(-x^2) carries the rounding of x^2, relative 6e-8 of it
    double worst_erfc = 0, worst_erf = 0, worst_inv = 0;
    for (int i = 0; i <= 4000; ++i) {   // erfc to x = 8, where it is 1e-29
        const double x = i * 0.002;
        worst_erfc = std::max(
            worst_erfc, std::abs(erfc_nonnegative(float(x)) / std::erfc(double(float(x))) - 1) / std::max(1.0, x * x));
        worst_erf = std::max(worst_erf, std::abs(erf_any(float(-x)) - std::erf(-x)));
    }
    for (int i = -9999; i <= 9999; ++i) {   // erfinv on (-1, 1): erf of it gives y back
        const double y = i * 1e-4, x = erfinv_any(float(y));
        worst_inv = std::max(worst_inv, std::abs(std::erf(x) - double(float(y))) / (1 - std::abs(y) + 1e-3));
    }
    // erfc^-1 in erfc's tail: erfc of it gives e back, relatively, from 1e-30 to 1.9
    double worst_cinv = 0;
    for (int i = 0; i <= 600; ++i) {
        const double e = std::pow(10.0, -30.0 + i * 0.05);
        if (e >= 1.9) break;
        const double x = erfcinv_any(float(e));
        worst_cinv = std::max(worst_cinv, std::abs(std::erfc(x) / double(float(e)) - 1) / std::max(1.0, x * x));
    }
    std::printf(
        "erfc relative / max(1, x^2) %.2e, erf absolute %.2e, erf(erfinv(y)) - y relative to 1 - |y| %.2e, "
        "erfc(erfcinv(e)) / e - 1 over max(1, x^2) %.2e\n",
        worst_erfc, worst_erf, worst_inv, worst_cinv);
    EXPECT_LT(worst_cinv, 1e-5);
    EXPECT_LT(worst_erfc, 5e-7);
    EXPECT_LT(worst_erf, 3e-7);
    EXPECT_LT(worst_inv, 1e-5);
    EXPECT_EQ(erfc_nonnegative(INFINITY), 0.0f);
    EXPECT_EQ(erf_any(INFINITY), 1.0f);
    EXPECT_TRUE(std::isfinite(erfinv_any(1.0f)) && std::isfinite(erfinv_any(-1.0f)));
}

// The projected areas: D integrates to 1 over the macro-surface, and to cos theta (1 + Lambda(w)) towards w.
TEST(Microsurface, BeckmannLambdaIsTheProjectedArea) {
    double worst = 0;
    for (double alpha : {0.05, 0.3, 1.0}) {
        const double norm = over_microfacets(alpha, [](glm::vec3 m) { return double(m.z); });
        EXPECT_NEAR(norm, 1.0, 1e-5) << "alpha " << alpha;
        for (double theta : {0.0, 30.0, 60.0, 80.0, 89.0, 89.9}) {
            const glm::vec3 w = dir_from_theta(theta);
            const double area = over_microfacets(alpha, [&](glm::vec3 m) { return std::max(0.0, double(dot(w, m))); });
            const double closed = double(w.z) * (1.0 + double(beckmann_lambda(w, float(alpha))));
            std::printf("alpha %.2f theta %5.1f: projected area %.7f, cos (1 + Lambda) %.7f\n", alpha, theta, area,
                        closed);
            worst = std::max(worst, std::abs(closed / area - 1));
            EXPECT_NEAR(closed / area, 1.0, 2e-5) << "alpha " << alpha << " theta " << theta;
        }
    }
    std::printf("worst relative difference %.2e\n", worst);
    EXPECT_EQ(beckmann_lambda(vec3(0.0f, 0.0f, 1.0f), 0.3f), 0.0f);   // normal incidence
    EXPECT_EQ(beckmann_G1(vec3(1.0f, 0.0f, 0.0f), 0.3f), 0.0f);   // the horizon: never NaN
}

struct SamplerCase {
    double alpha, theta;
};

// The reflected direction of a sampled visible normal, against its density D_wi(m) / (4 wi.m) (as pdf_conductor).
// At 89 degrees the density's peak at the horizon needs the finer grid: on the coarser one the density's own
// quadrature is 7e-4 short of 1 there, and GGX's exact sampler fails as well (p 2e-6 with 1e6 samples).
chi2::Result reflection_chi2(const SamplerCase& c, uint32_t id, float pdf_alpha_scale = 1.0f) {
    const bool grazing = c.theta > 85.0;
    const glm::vec3 wi = dir_from_theta(c.theta);
    const float a = float(c.alpha);
    return chi2::test(
        [=](int i) {
            const vec4 u = uniform4(id, i);
            const vec3 m = sample_beckmann_visible_normal(wi, a, u.x, u.y);
            return glm::vec3(2.0f * dot(wi, m) * m - wi);
        },
        [=](glm::vec3 wo) {
            glm::vec3 h = glm::normalize(wi + wo);
            const double c_ih = dot(wi, h);
            if (c_ih <= 0) return 0.0;
            return double(beckmann_visible_normal_pdf(wi, h, a * pdf_alpha_scale)) / (4 * c_ih);
        },
        500000, grazing ? 80 : 40, grazing ? 160 : 80, grazing ? 48 : 24);
}

TEST(Microsurface, BeckmannVisibleNormalsChiSquare) {
    std::vector<SamplerCase> cases;
    for (double alpha : {0.15, 0.4, 1.0})
        for (double theta : {0.0, 0.5, 50.0, 80.0, 89.0}) cases.push_back({alpha, theta});
    const double level = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(cases.size()));   // Sidak
    uint32_t id = 0;
    for (const SamplerCase& c : cases) {
        const chi2::Result r = reflection_chi2(c, id++);
        std::printf("beckmann visible normals alpha=%.2f theta=%4.1f: chi2 %8.1f dof %4d p %.4f integral %.5f\n",
                    c.alpha, c.theta, r.chi2, r.dof, r.p_value, r.pdf_integral);
        EXPECT_TRUE(r.failure.empty()) << r.failure;
        EXPECT_GT(r.p_value, level) << "alpha " << c.alpha << " theta " << c.theta;
    }
}

// The test can fail: the density of a 5% rougher surface is told apart from the sampler's.
TEST(Microsurface, BeckmannChiSquareRejectsAWrongDensity) {
    EXPECT_LT(reflection_chi2({0.4, 50.0}, 999u, 1.05f).p_value, 1e-6);
}

// Single scattering with F = 1: the albedo the walk's estimator gives (visible normals, weight G2 / G1 for the
// height-correlated G2 = 1 / (1 + Lambda_i + Lambda_o), G1(wo) for the separable G1 G1; a direction below the surface
// lost) against the integral of f cos = D G2 / (4 wi.z) over the upper hemisphere (in the half vector, dwo = 4 (wo.h)
// dh).
TEST(Microsurface, BeckmannAlbedoSampledAsTheWalkDoes) {
    for (double alpha : {0.1, 0.5, 1.0})
        for (double theta : {0.0, 45.0, 75.0})
            for (bool separable : {false, true}) {
                const glm::vec3 wi = dir_from_theta(theta);
                const float a = float(alpha);
                auto G2 = [&](glm::vec3 wo) {
                    const float li = beckmann_lambda(wi, a), lo = beckmann_lambda(wo, a);
                    return separable ? 1.0 / ((1.0 + li) * (1.0 + lo)) : 1.0 / (1.0 + li + lo);
                };
                const double integral = over_microfacets(
                    alpha,
                    [&](glm::vec3 h) {
                        const double c = dot(wi, h);
                        const glm::vec3 wo = 2.0f * float(c) * h - wi;
                        if (c <= 0 || wo.z <= 0) return 0.0;
                        return G2(wo) / (4 * wi.z) * 4 * c;
                    },
                    1000, 360);   // within 3e-6 of the 3000 x 720 rule's at every case here, far below the se
                const int n = 100000;
                double s = 0, s2 = 0;
                for (int i = 0; i < n; ++i) {
                    const vec4 u = uniform4(5000u + uint32_t(theta * 10 + alpha * 1000), i);
                    const vec3 m = sample_beckmann_visible_normal(wi, a, u.x, u.y);
                    const vec3 wo = 2.0f * dot(wi, m) * m - wi;
                    const double w = wo.z > 0 ? G2(wo) * (1.0 + beckmann_lambda(wi, a)) : 0.0;
                    s += w;
                    s2 += w * w;
                }
                const double mean = s / n, se = std::sqrt((s2 / n - mean * mean) / n);
                std::printf("alpha %.1f theta %4.1f %-18s albedo: integral %.6f, sampled %.6f +- %.6f\n", alpha, theta,
                            separable ? "separable" : "height-correlated", integral, mean, se);
                EXPECT_LT(std::abs(mean - integral), 4 * se + 1e-6)
                    << "alpha " << alpha << " theta " << theta << (separable ? " separable" : "");
            }
}

}   // namespace
