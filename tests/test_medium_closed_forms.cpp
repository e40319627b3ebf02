// Scattering media against their closed forms, before the walk takes them: the closed forms themselves
// (tests/exact_media.h: Chandrasekhar's H-function and its identities), and a small random walk built from the
// medium's own samplers (shaders/lib/medium.glsl through GLM) under an index-matched smooth top: single scattering
// in a thin slab with Henyey-Greenstein phase functions, and every order in a semi-infinite isotropic medium, bin
// by bin in the outgoing direction.
#include "compat.glsl"
#include "rng.glsl"
#include "medium.glsl"
#include "exact_media.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace {

using exact_media::HFunction;

TEST(ClosedFormsOfMedia, HFunctionMeetsChandrasekharsIdentities) {
    // conservative scattering: H(1) = 2.90781 (Chandrasekhar 1960, table XI), int H = 2
    HFunction h1(1.0);
    EXPECT_NEAR(h1(1.0), 2.90781, 2e-5);
    EXPECT_NEAR(h1(0.0), 1.0, 1e-12);
    for (double omega : {0.2, 0.5, 0.9, 0.99, 1.0}) {
        HFunction H(omega);
        // zeroth moment: int_0^1 H = (2 / omega) (1 - sqrt(1 - omega))
        EXPECT_NEAR(H.integral(), 2.0 / omega * (1 - std::sqrt(1 - omega)), 2e-6) << "omega " << omega;
        // the BRDF's directional albedo, integrated here, = 1 - H(mu_i) sqrt(1 - omega)
        for (double mu_i : {0.1, 0.5, 1.0}) {
            const int n = 20000;
            double a = 0;
            for (int k = 0; k < n; ++k) {
                double mu_o = (k + 0.5) / n;
                a += exact_media::semi_infinite_isotropic_brdf(H, mu_i, mu_o, omega) * mu_o * 2 * M_PI / n;
            }
            EXPECT_NEAR(a, 1 - H(mu_i) * std::sqrt(1 - omega), 2e-4) << "omega " << omega << " mu_i " << mu_i;
        }
    }
}

// A path through a plane-parallel medium of optical thickness tau (extinction 1 per unit length, so lengths are
// optical depths) under an index-matched smooth top and over a black index-matched bottom, analog absorption
// (a collision scatters with probability omega). Returns the order (collisions) of a path leaving through the top
// and its direction there, or order -1 (absorbed, or left through the bottom).
struct Exit {
    int order;
    glm::vec3 d;
};

Exit trace(glm::vec3 wi, double tau, double omega, float g, uint32_t path, uint32_t stream) {
    Rng rng = rng_init(path, 0u, 777u, stream);
    glm::vec3 d = -wi;   // propagation
    double z = 0;   // height: 0 at the top, -tau at the bottom
    for (int order = 0; order < 100000; ++order) {
        const double s_max = d.z < 0 ? (z + tau) / -d.z : -z / d.z;
        vec4 u = rng_next4(rng);
        FreeFlight f = sample_free_flight(vec3(1.0f), float(s_max), vec3(1.0f, 0.0f, 0.0f), u.x, u.y);
        if (!f.scattered) return d.z > 0 ? Exit{order, d} : Exit{-1, d};
        z += d.z * f.s;
        if (u.z >= omega) return {-1, d};
        vec4 v = rng_next4(rng);
        d = sample_henyey_greenstein(d, g, v.x, v.y);
    }
    return {-1, d};
}

// Bins of the outgoing direction: n_mu bands of equal projected solid angle (mu^2 uniform), n_phi in azimuth.
struct Bins {
    int n_mu, n_phi;
    int index(glm::vec3 d) const {
        int a = std::min(n_mu - 1, int(double(d.z) * d.z * n_mu));
        double phi = std::atan2(double(d.y), double(d.x));
        if (phi < 0) phi += 2 * M_PI;
        int b = std::min(n_phi - 1, int(phi / (2 * M_PI) * n_phi));
        return a * n_phi + b;
    }
    // int over the bin of f mu dw (f given as f(mu, phi)), by midpoint quadrature in (mu^2, phi): mu dw = d(mu^2) / 2 dphi
    double integral(int bin, const std::function<double(double mu, double phi)>& f, int sub = 64) const {
        const int a = bin / n_phi, b = bin % n_phi;
        double s = 0;
        for (int i = 0; i < sub; ++i)
            for (int j = 0; j < sub; ++j) {
                double mu2 = (a + (i + 0.5) / sub) / n_mu, phi = (b + (j + 0.5) / sub) / n_phi * 2 * M_PI;
                s += f(std::sqrt(mu2), phi);
            }
        return s / (sub * sub) * (0.5 / n_mu) * (2 * M_PI / n_phi);
    }
};

// Compare the walk's energy per bin with the closed form's, bin by bin: |estimate - exact| < 4.5 se + 1e-4 of
// the exact (the quadrature's own error).
void compare_bins(const Bins& bins, const std::vector<double>& got, int n, const std::vector<double>& want,
                  const char* what) {
    double total_got = 0, total_want = 0;
    for (size_t b = 0; b < got.size(); ++b) {
        const double p = got[b] / n, se = std::sqrt(p * (1 - p) / n);
        EXPECT_LE(std::fabs(p - want[b]), 4.5 * se + 1e-4 * want[b])
            << what << ": bin " << b << " (mu^2 band " << b / bins.n_phi << ", phi bin " << b % bins.n_phi << "): walk "
            << p << " +- " << se << ", closed form " << want[b];
        total_got += p;
        total_want += want[b];
    }
    std::printf("%s: albedo walk %.5f, closed form %.5f\n", what, total_got, total_want);
}

TEST(ClosedFormsOfMedia, SingleScatteringInAThinSlab) {
    struct Case {
        double tau, omega;
        float g;
        double theta_i_deg;
    };
    uint32_t stream = 0;
    for (const Case& c : {Case{0.5, 0.8, 0.6f, 40.0}, Case{0.2, 1.0, -0.3f, 70.0}, Case{1.0, 0.5, 0.0f, 0.0},
                          Case{0.3, 0.9, 0.9f, 60.0}}) {
        const double ti = c.theta_i_deg * M_PI / 180;
        const glm::vec3 wi(float(std::sin(ti)), 0.0f, float(std::cos(ti)));
        const Bins bins{8, 12};
        const int n = 400000;
        std::vector<double> got(bins.n_mu * bins.n_phi, 0), want(got.size());
        for (int i = 0; i < n; ++i) {
            Exit e = trace(wi, c.tau, c.omega, c.g, uint32_t(i), stream);
            if (e.order == 1) got[bins.index(e.d)] += 1;
        }
        ++stream;
        for (size_t b = 0; b < want.size(); ++b)
            want[b] = bins.integral(
                int(b),
                [&](double mu, double phi) {
                    double st = std::sqrt(std::max(0.0, 1 - mu * mu));
                    glm::dvec3 wo(st * std::cos(phi), st * std::sin(phi), mu);
                    double cos_scatter = glm::dot(-glm::dvec3(wi), wo);
                    double p = phase_hg(float(cos_scatter), c.g);
                    return exact_media::single_scattering_brdf(std::cos(ti), mu, p, c.tau, c.omega);
                },
                c.g > 0.8f ? 192 : 64);
        char what[128];
        std::snprintf(what, sizeof what, "single scattering tau %g omega %g g %g theta_i %g", c.tau, c.omega, c.g,
                      c.theta_i_deg);
        compare_bins(bins, got, n, want, what);
    }
}

TEST(ClosedFormsOfMedia, SemiInfiniteIsotropicMediumEveryOrder) {
    uint32_t stream = 100;
    for (double omega : {0.5, 0.9}) {
        for (double theta_i_deg : {0.0, 30.0, 75.0}) {
            const double ti = theta_i_deg * M_PI / 180, mu_i = std::cos(ti);
            const glm::vec3 wi(float(std::sin(ti)), 0.0f, float(mu_i));
            const Bins bins{10, 1};   // the multiple-scattering BRDF of isotropic scattering does not depend on phi
            const int n = 300000;
            HFunction H(omega);
            std::vector<double> got(bins.n_mu, 0), want(bins.n_mu);
            for (int i = 0; i < n; ++i) {
                Exit e = trace(wi, 1e3, omega, 0.0f, uint32_t(i), stream);
                if (e.order >= 1) got[bins.index(e.d)] += 1;
            }
            ++stream;
            for (int b = 0; b < bins.n_mu; ++b)
                want[b] = bins.integral(b, [&](double mu, double) {
                    return exact_media::semi_infinite_isotropic_brdf(H, mu_i, mu, omega);
                });
            char what[128];
            std::snprintf(what, sizeof what,
                          "semi-infinite isotropic omega %g theta_i %g (albedo 1 - H sqrt(1 - omega) "
                          "= %.5f)",
                          omega, theta_i_deg, 1 - H(mu_i) * std::sqrt(1 - omega));
            compare_bins(bins, got, n, want, what);
        }
    }
}

}   // namespace
