// The SGGX microflake medium's functions (shaders/lib/medium.glsl, compiled as C++ through GLM) against what they
// must be (Heitz, Dupuy, Crassin & Dachsbacher 2015, "The SGGX microflake distribution"):
// - the fibres' D against its closed form sigma^3 / (pi (cos^2 + sigma^2 sin^2)^2) (S = diag(1, 1, sigma^2));
// - the projected area sqrt(w^T S w) against the integral of <w, m>+ D(m) over the sphere (Eq. 9 from Eq. 7);
// - the specular phase function normalised over the sphere, and reciprocal: sigma(wi) f(wi, wo) = sigma(wo) f(wo, wi);
// - the sampler's directions by chi-square against the phase function, with a negative control;
// - finite, unit directions at the roughness range's end (alpha 0.01) and at grazing directions.
#include "chi2.h"
#include "compat.glsl"
#include "rng.glsl"
#include "medium.glsl"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

namespace {

vec4 uniform4(uint32_t stream, int i) {
    Rng r = rng_init(uint32_t(i), 0u, 9191u + stream, 13u);
    return rng_next4(r);
}

glm::vec3 from_angles(double theta_deg, double phi_deg) {
    const double t = theta_deg * M_PI / 180, p = phi_deg * M_PI / 180;
    return glm::vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t)));
}

// The integral over the sphere of f(w), by a midpoint rule in (cos theta, phi), n_cos x n_phi cells
double sphere_integral(const std::function<double(glm::dvec3)>& f, int n_cos = 2000, int n_phi = 400) {
    double acc = 0;
    for (int i = 0; i < n_cos; ++i) {
        const double c = -1 + (i + 0.5) * 2.0 / n_cos, s = std::sqrt(std::max(0.0, 1 - c * c));
        for (int j = 0; j < n_phi; ++j) {
            const double p = (j + 0.5) * 2 * M_PI / n_phi;
            acc += f(glm::dvec3(s * std::cos(p), s * std::sin(p), c));
        }
    }
    return acc * (2.0 / n_cos) * (2 * M_PI / n_phi);
}

struct Medium {
    const char* name;
    uint phase;
    float alpha;
};
const Medium kMedia[] = {{"fibres", MEDIUM_PHASE_SGGX_FIBRE, 1.0f},
                         {"fibres", MEDIUM_PHASE_SGGX_FIBRE, 0.6f},
                         {"fibres", MEDIUM_PHASE_SGGX_FIBRE, 0.35f},
                         {"flakes", MEDIUM_PHASE_SGGX_FLAKE, 0.6f},
                         {"flakes", MEDIUM_PHASE_SGGX_FLAKE, 0.35f}};

TEST(Sggx, FibreDistributionMatchesItsClosedForm) {
    for (float alpha : {1.0f, 0.5f, 0.1f, 0.01f}) {
        const vec3 S = sggx_diagonal(MEDIUM_PHASE_SGGX_FIBRE, alpha);
        const double sigma = double(alpha) * alpha;
        for (double th : {0.0, 10.0, 45.0, 80.0, 90.0}) {
            const double c = std::cos(th * M_PI / 180), s2 = 1 - c * c;
            const double q = c * c + sigma * sigma * s2;
            const double want = sigma * sigma * sigma / (M_PI * q * q);
            EXPECT_NEAR(sggx_ndf(S, from_angles(th, 30.0)), want, 2e-5 * want) << "alpha " << alpha << " theta " << th;
        }
        // an isotropic S (alpha 1) has D = 1 / pi everywhere and unit projected area
        if (alpha == 1.0f) {
            EXPECT_NEAR(sggx_ndf(S, from_angles(37.0, 11.0)), 1 / M_PI, 1e-6);
            EXPECT_NEAR(sggx_projected_area(S, from_angles(63.0, 200.0)), 1.0, 1e-6);
        }
    }
}

TEST(Sggx, ProjectedAreaIsTheIntegralOfVisibleNormals) {
    for (const Medium& m : kMedia) {
        const vec3 S = sggx_diagonal(m.phase, m.alpha);
        for (double th : {0.0, 35.0, 70.0, 90.0}) {
            const glm::vec3 w = from_angles(th, 20.0);
            const double area = sphere_integral([&](glm::dvec3 n) {
                const double c = glm::dot(glm::dvec3(w), n);
                return c > 0 ? c * double(sggx_ndf(S, glm::vec3(n))) : 0.0;
            });
            EXPECT_NEAR(area, sggx_projected_area(S, w), 2e-3 * sggx_projected_area(S, w))
                << m.name << " alpha " << m.alpha << " theta " << th;
        }
    }
}

TEST(Sggx, PhaseFunctionIsNormalisedAndReciprocal) {
    for (const Medium& m : kMedia) {
        const vec3 S = sggx_diagonal(m.phase, m.alpha);
        for (double th : {0.0, 35.0, 70.0, 90.0, 150.0}) {
            const glm::vec3 wi = from_angles(th, 50.0);
            // from a direction at or below the horizon the flakes' lobe hugs the backward direction -wi, within
            // 2 sigma^2 in azimuth (wo = 2 <wi, h> h - wi with h near the normal): a finer grid in azimuth there
            const double total =
                sphere_integral([&](glm::dvec3 wo) { return double(phase_sggx_specular(S, wi, glm::vec3(wo))); }, 3000,
                                th >= 90.0 ? 4000 : 600);
            EXPECT_NEAR(total, 1.0, 3e-3) << m.name << " alpha " << m.alpha << " theta_i " << th;
            for (double to : {5.0, 60.0, 120.0, 175.0}) {
                const glm::vec3 wo = from_angles(to, 200.0);
                const double a = sggx_projected_area(S, wi) * phase_sggx_specular(S, wi, wo);
                const double b = sggx_projected_area(S, wo) * phase_sggx_specular(S, wo, wi);
                EXPECT_NEAR(a, b, 1e-5 * std::max(a, 1e-3)) << m.name << " reciprocity " << th << " " << to;
            }
        }
    }
}

// Directions after a specular flake against the phase function, at Sidak's level over every case
TEST(Sggx, DirectionsFollowThePhaseFunction) {
    const glm::vec3 ds[] = {glm::vec3(0, 0, -1), glm::normalize(glm::vec3(0.6f, -0.3f, -0.5f)),
                            glm::normalize(glm::vec3(0.99f, 0.0f, 0.1f))};
    const int cases = int(std::size(kMedia) * std::size(ds));
    const double level = 1.0 - std::pow(1.0 - 0.01, 1.0 / cases);
    uint32_t stream = 0;
    for (const Medium& m : kMedia) {
        const vec3 S = sggx_diagonal(m.phase, m.alpha);
        for (glm::vec3 d : ds) {
            const uint32_t id = stream++;
            chi2::Result r = chi2::test(
                [&](int i) {
                    vec4 u = uniform4(id, i);
                    return sample_sggx_specular(S, d, u.x, u.y);
                },
                [&](glm::vec3 w) { return double(phase_sggx_specular(S, -d, w)); }, 400000, 40, 80, 48);
            EXPECT_TRUE(r.failure.empty()) << r.failure;
            EXPECT_NEAR(r.pdf_integral, 1.0, 5e-3) << m.name << " alpha " << m.alpha;
            EXPECT_GT(r.p_value, level) << m.name << " alpha " << m.alpha << " d (" << d.x << ", " << d.y << ", " << d.z
                                        << "): chi2 " << r.chi2 << " dof " << r.dof;
            std::printf("SGGX %s alpha %.2f d (%+.2f %+.2f %+.2f): chi2/dof %.3f p %.3g\n", m.name, m.alpha, d.x, d.y,
                        d.z, r.chi2 / std::max(1, r.dof), r.p_value);
        }
    }
}

// The test can fail: the same directions against the phase function of another roughness are rejected
TEST(Sggx, ChiSquareRejectsAnotherRoughness) {
    const vec3 S = sggx_diagonal(MEDIUM_PHASE_SGGX_FIBRE, 0.6f), wrong = sggx_diagonal(MEDIUM_PHASE_SGGX_FIBRE, 0.66f);
    const glm::vec3 d = glm::normalize(glm::vec3(0.6f, -0.3f, -0.5f));
    chi2::Result r = chi2::test(
        [&](int i) {
            vec4 u = uniform4(777u, i);
            return sample_sggx_specular(S, d, u.x, u.y);
        },
        [&](glm::vec3 w) { return double(phase_sggx_specular(wrong, -d, w)); }, 400000, 40, 80, 48);
    EXPECT_LT(r.p_value, 1e-6);
}

// At alpha 0.01 (S holds alpha^8 = 1e-16 in its determinant) and at grazing directions, every sampled direction is a
// finite unit vector, and the phase function and projected area are finite
TEST(Sggx, FiniteAtTheEndsOfItsRange) {
    for (uint phase : {MEDIUM_PHASE_SGGX_FIBRE, MEDIUM_PHASE_SGGX_FLAKE})
        for (float alpha : {0.01f, 0.02f, 1.0f}) {
            const vec3 S = sggx_diagonal(phase, alpha);
            for (glm::vec3 d :
                 {glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0),
                  glm::normalize(glm::vec3(1.0f, 0.0f, -1.7e-3f)), glm::normalize(glm::vec3(1e-3f, 0, 1))})
                for (int i = 0; i < 20000; ++i) {
                    vec4 u = uniform4(phase * 100u + uint32_t(alpha * 50), i);
                    const glm::vec3 w = sample_sggx_specular(S, d, u.x, u.y);
                    ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z) &&
                                std::fabs(glm::length(w) - 1.0f) < 1e-4f)
                        << "phase " << phase << " alpha " << alpha << " sample " << i;
                    const float f = phase_sggx_specular(S, -d, w), a = sggx_projected_area(S, d);
                    ASSERT_TRUE(std::isfinite(f) && f >= 0.0f && std::isfinite(a) && a > 0.0f);
                }
        }
}

// A user's model reads a medium's phase as GONIO_PHASE_* (shaders/lib/models/user_model.glsl, which does not include
// medium.glsl): the same values as MEDIUM_PHASE_*
TEST(Sggx, UserModelPhaseConstantsAreTheWalks) {
    std::ifstream in(std::string(GONIO_SOURCE_DIR) + "/shaders/lib/models/user_model.glsl");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (auto [name, value] : {std::pair<const char*, uint>{"GONIO_PHASE_HG", MEDIUM_PHASE_HG},
                               {"GONIO_PHASE_SGGX_FIBRE", MEDIUM_PHASE_SGGX_FIBRE},
                               {"GONIO_PHASE_SGGX_FLAKE", MEDIUM_PHASE_SGGX_FLAKE}})
        EXPECT_NE(text.find("const uint " + std::string(name) + " = " + std::to_string(value) + "u;"),
                  std::string::npos)
            << name;
}

}   // namespace
