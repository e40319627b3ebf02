// The samplers of a scattering medium (shaders/lib/medium.glsl, compiled as C++ through GLM) against their
// densities: Henyey-Greenstein directions by chi-square on the sphere, free-flight distances by chi-square on
// [0, s_max] plus the boundary, and the RGB free flight's weights by their expectations per channel.
#include "chi2.h"
#include "compat.glsl"
#include "rng.glsl"
#include "medium.glsl"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

vec4 uniform4(uint32_t stream, int i) {
    Rng r = rng_init(uint32_t(i), 0u, 4242u + stream, 11u);
    return rng_next4(r);
}

// Sidak over the cases of each test: a sampler passes at p > 1 - (1 - 0.01)^(1/cases)
double sidak(int cases) { return 1.0 - std::pow(1.0 - 0.01, 1.0 / cases); }

TEST(HenyeyGreenstein, PhaseIsNormalisedAndMatchesItsClosedForm) {
    for (float g : {-0.9f, -0.3f, 0.0f, 5e-5f, 0.5f, 0.95f}) {
        // integral over the sphere: 2 pi int_{-1}^{1} p(mu) dmu, by a fine midpoint rule in mu
        const int n = 400000;
        double s = 0;
        for (int i = 0; i < n; ++i) s += phase_hg(float(-1.0 + (i + 0.5) * 2.0 / n), g);
        EXPECT_NEAR(s * 2.0 / n * 2 * M_PI, 1.0, 2e-4) << "g " << g;
        // forward and backward peaks: p(1) = (1 + g) / (4 pi (1 - g)^2), p(-1) = (1 - g) / (4 pi (1 + g)^2)
        EXPECT_NEAR(phase_hg(1.0f, g), (1 + g) / (4 * M_PI * (1 - g) * (1 - g)), 1e-4 * phase_hg(1.0f, g));
        EXPECT_NEAR(phase_hg(-1.0f, g), (1 - g) / (4 * M_PI * (1 + g) * (1 + g)), 1e-4 * phase_hg(-1.0f, g));
    }
}

TEST(HenyeyGreenstein, SampledCosineIsFiniteAtTheEndsOfU) {
    for (float g : {-0.999f, -0.9f, -1e-3f, -9e-5f, 0.0f, 9e-5f, 1e-3f, 0.5f, 0.95f, 0.999f})
        for (float u : {0.0f, 1e-7f, 0.5f, 0.9999999f, 1.0f}) {
            float c = sample_hg_cos(g, u);
            EXPECT_TRUE(std::isfinite(c) && c >= -1.0f && c <= 1.0f) << "g " << g << " u " << u << " cos " << c;
        }
    EXPECT_EQ(sample_hg_cos(0.5f, 0.0f), -1.0f);
    EXPECT_EQ(sample_hg_cos(0.5f, 1.0f), 1.0f);
}

// Each g's directions (three incident directions) by chi-square against the phase function, at Sidak's level over
// `cases` cases; streams numbered from `stream`
void expect_hg_directions_follow_phase(std::initializer_list<float> gs, int cases, uint32_t stream) {
    const double level = sidak(cases);
    for (float g : gs)
        for (glm::vec3 d : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(0.6f, -0.3f, 0.5f))}) {
            const uint32_t id = stream++;
            // a peaked lobe off the pole is resolved by a finer quadrature sub-grid
            const int sub = g > 0.9f ? 160 : 24;
            chi2::Result r = chi2::test(
                [&](int i) {
                    vec4 u = uniform4(id, i);
                    return sample_henyey_greenstein(d, g, u.x, u.y);
                },
                [&](glm::vec3 w) { return double(phase_hg(glm::dot(d, w), g)); }, 400000, 40, 80, sub);
            EXPECT_TRUE(r.failure.empty()) << r.failure;
            EXPECT_NEAR(r.pdf_integral, 1.0, 5e-3) << "g " << g;
            EXPECT_GT(r.p_value, level) << "g " << g << " d (" << d.x << ", " << d.y << ", " << d.z << "): chi2 "
                                        << r.chi2 << " dof " << r.dof;
            std::printf("HG g %+.2f d (%+.2f %+.2f %+.2f): chi2/dof %.3f p %.3g\n", g, d.x, d.y, d.z,
                        r.chi2 / std::max(1, r.dof), r.p_value);
        }
}

// Sidak's level over all 18 cases of both tests, as when they were one
TEST(HenyeyGreenstein, DirectionsFollowThePhaseFunction) {
    expect_hg_directions_follow_phase({-0.9f, -0.5f, 0.0f, 0.3f, 0.8f}, 18, 0u);
}

// g 0.95: its lobe needs the finer quadrature (about 10 s; labelled slow)
TEST(HenyeyGreenstein, DirectionsFollowAPeakedPhaseFunction) { expect_hg_directions_follow_phase({0.95f}, 18, 15u); }

// Pearson chi-square of sampled distances against the mixture density: n_bins equal bins on [0, s_hi), s_hi the
// smaller of s_max and 10 mean free paths of the thinnest channel, one cell [s_hi, s_max), and the boundary.
double free_flight_p_value(glm::vec3 sigma, float s_max, glm::vec3 prob, uint32_t stream, int n, int n_bins) {
    double thinnest = 0;
    for (int k = 0; k < 3; ++k)
        if (sigma[k] > 0 && (thinnest == 0 || sigma[k] < thinnest)) thinnest = sigma[k];
    const double s_hi = thinnest > 0 ? std::min(double(s_max), 10.0 / thinnest) : double(s_max);
    std::vector<double> edges;
    for (int b = 0; b <= n_bins; ++b) edges.push_back(s_hi * b / n_bins);
    if (s_hi < s_max) edges.push_back(s_max);
    const int cells_in = int(edges.size()) - 1;   // then the boundary
    std::vector<double> obs(cells_in + 1, 0), expct(cells_in + 1, 0);
    for (int i = 0; i < n; ++i) {
        vec4 u = uniform4(stream, i);
        FreeFlight f = sample_free_flight(sigma, s_max, prob, u.x, u.y);
        EXPECT_TRUE(std::isfinite(f.s) && f.s >= 0 && f.s <= s_max);
        EXPECT_EQ(f.scattered, f.s < s_max);
        int cell = cells_in;
        if (f.scattered) cell = int(std::upper_bound(edges.begin(), edges.end(), double(f.s)) - edges.begin()) - 1;
        obs[std::clamp(cell, 0, cells_in)] += 1;
    }
    // the mixture's probabilities: channel k puts exp(-sigma a) - exp(-sigma b) in [a, b), exp(-sigma s_max) beyond
    for (int k = 0; k < 3; ++k) {
        const double sk = sigma[k];
        for (int b = 0; b < cells_in; ++b)
            expct[b] += prob[k] * (std::exp(-sk * edges[b]) - std::exp(-sk * edges[b + 1])) * n;
        expct[cells_in] += prob[k] * std::exp(-sk * double(s_max)) * n;
    }
    double chi = 0;
    int cells = 0;
    for (int b = 0; b <= cells_in; ++b) {
        if (expct[b] < 5) {
            EXPECT_LT(obs[b], 5 + 5 * std::sqrt(5.0)) << "cell " << b;
            continue;
        }
        chi += (obs[b] - expct[b]) * (obs[b] - expct[b]) / expct[b];
        ++cells;
    }
    EXPECT_GE(cells, 10);
    return gonio::gamma_q((cells - 1) / 2.0, chi / 2.0);
}

struct FlightCase {
    glm::vec3 sigma;
    float s_max;
    glm::vec3 prob;
};

std::vector<FlightCase> flight_cases() {
    return {{glm::vec3(1.0f), 1.0f, glm::vec3(1, 0, 0)},
            {glm::vec3(0.1f), 2.0f, glm::vec3(1.0f / 3)},
            {glm::vec3(5.0f), 1.0f, glm::vec3(1.0f / 3)},
            {glm::vec3(0.5f, 2.0f, 8.0f), 1.0f, glm::vec3(1.0f / 3)},
            {glm::vec3(0.5f, 2.0f, 8.0f), 3.0f, glm::vec3(0.6f, 0.3f, 0.1f)},
            {glm::vec3(0.0f, 1.0f, 50.0f), 1.5f, glm::vec3(0.2f, 0.5f, 0.3f)},
            {glm::vec3(1e4f, 1e4f, 1e4f), 1.0f, glm::vec3(1.0f / 3)}};
}

TEST(FreeFlight, DistancesFollowTheMixtureDensity) {
    auto cases = flight_cases();
    const double level = sidak(int(cases.size()));
    uint32_t stream = 100;
    for (const FlightCase& c : cases) {
        double p = free_flight_p_value(c.sigma, c.s_max, c.prob, stream++, 400000, 50);
        EXPECT_GT(p, level) << "sigma (" << c.sigma.x << ", " << c.sigma.y << ", " << c.sigma.z << ") s_max "
                            << c.s_max;
    }
}

// The estimator per channel: E[weight; reached] = exp(-sigma s_max) and E[weight; scattered in [a, b)] =
// exp(-sigma a) - exp(-sigma b), each channel on its own, whatever channel the flight was drawn in.
TEST(FreeFlight, WeightsAreUnbiasedInEveryChannel) {
    uint32_t stream = 200;
    for (const FlightCase& c : flight_cases()) {
        const int n = 400000;
        const double a = 0.25 * c.s_max, b = 0.5 * c.s_max;
        double reach[3] = {0, 0, 0}, reach2[3] = {0, 0, 0}, band[3] = {0, 0, 0}, band2[3] = {0, 0, 0};
        for (int i = 0; i < n; ++i) {
            vec4 u = uniform4(stream, i);
            FreeFlight f = sample_free_flight(c.sigma, c.s_max, c.prob, u.x, u.y);
            for (int k = 0; k < 3; ++k) {
                ASSERT_TRUE(std::isfinite(f.weight[k]) && f.weight[k] >= 0) << f.weight[k];
                double w = f.weight[k];
                // the scattering estimate of the band: sigma exp(-sigma s) / p(s) integrates to the band's mass
                if (f.scattered && f.s >= a && f.s < b) band[k] += w, band2[k] += w * w;
                if (!f.scattered) reach[k] += w, reach2[k] += w * w;
            }
        }
        ++stream;
        for (int k = 0; k < 3; ++k) {
            const double sk = c.sigma[k];
            const double want_reach = std::exp(-sk * c.s_max), want_band = std::exp(-sk * a) - std::exp(-sk * b);
            auto check = [&](double sum, double sum2, double want, const char* what) {
                double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
                EXPECT_LE(std::fabs(mean - want), 4.5 * se + 1e-12)
                    << what << " channel " << k << " sigma " << sk << " s_max " << c.s_max << ": " << mean << " vs "
                    << want << " (se " << se << ")";
            };
            check(reach[k], reach2[k], want_reach, "reached");
            check(band[k], band2[k], want_band, "scattered in [s_max/4, s_max/2)");
        }
    }
}

}   // namespace

namespace {

// What the channel's choice leaves (FreeFlight::u_rest, the walk's Russian roulette number) is uniform on [0, 1)
// and independent of the flight: chi-square of its histogram against uniform, for each channel's flights apart, and
// within each of them for flights that collide and flights that reach the interface apart.
TEST(FreeFlight, LeftOverUniformIsUniformAndIndependent) {
    auto cases = flight_cases();
    const int cells = 20;
    const double level = sidak(int(cases.size()) * 6);
    uint32_t stream = 300;
    for (const FlightCase& c : cases) {
        std::vector<std::vector<double>> obs(6, std::vector<double>(cells, 0));   // channel x (scattered, reached)
        const int n = 300000;
        for (int i = 0; i < n; ++i) {
            vec4 u = uniform4(stream, i);
            FreeFlight f = sample_free_flight(c.sigma, c.s_max, c.prob, u.x, u.y);
            ASSERT_TRUE(f.u_rest >= 0.0f && f.u_rest < 1.0f) << f.u_rest;
            const int channel = u.x < c.prob.x ? 0 : (u.x < c.prob.x + c.prob.y ? 1 : 2);
            obs[size_t(channel * 2 + (f.scattered ? 0 : 1))][size_t(std::min(cells - 1, int(f.u_rest * cells)))] += 1;
        }
        ++stream;
        for (size_t g = 0; g < obs.size(); ++g) {
            double total = 0;
            for (double o : obs[g]) total += o;
            if (total < 20.0 * cells) continue;   // a channel (or outcome) too rare to test
            double chi = 0;
            for (double o : obs[g]) chi += (o - total / cells) * (o - total / cells) / (total / cells);
            EXPECT_GT(gonio::gamma_q((cells - 1) / 2.0, chi / 2.0), level)
                << "channel " << g / 2 << (g % 2 ? " reached" : " scattered") << ", sigma (" << c.sigma.x << ", "
                << c.sigma.y << ", " << c.sigma.z << ")";
        }
    }
}

}   // namespace
