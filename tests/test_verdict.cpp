// The verdict statistics (host/models/compare.h, Agreement; docs/MODELS.md "Verdicts") tested as statistics:
//  - the distribution functions against tabulated values;
//  - on synthetic gonio-photometer runs drawn from a known distribution (no device): a model equal to the truth is
//    rejected at about the nominal rate, never more than twice it, its chi2/dof averages 1; a model off by 5%
//    everywhere (a bias), or by +-10% in alternate theta rows (a shape error with the right albedo) is rejected;
//  - on the device: a model that is exact for its stack (ww-corrected over a black base is the coat's own
//    reflection, which the reference traces) is within the noise at every angle and seed, and the same model
//    scaled by 1 + 3 x its smallest detectable bias is not.
#include "compare.h"
#include "comparison.h"
#include "gpu_fixture.h"
#include "models.h"
#include "statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gonio;
using namespace gonio_test;

TEST(Statistics, DistributionFunctionsMatchTables) {
    // chi-square upper tail: the 5% and 1% points for 1, 10 and 100 degrees of freedom (Abramowitz & Stegun 26.8)
    EXPECT_NEAR(chi2_p_value(3.841459, 1), 0.05, 1e-6);
    EXPECT_NEAR(chi2_p_value(23.209251, 10), 0.01, 1e-6);
    EXPECT_NEAR(chi2_p_value(124.342113, 100), 0.05, 1e-6);
    EXPECT_NEAR(chi2_p_value(20000 + 2.326348 * std::sqrt(40000.0), 20000), 0.01, 2e-3);   // ~ normal for large k
    EXPECT_NEAR(normal_two_sided_p(1.959964), 0.05, 1e-6);
    EXPECT_NEAR(normal_upper_quantile(0.005), 2.575829, 1e-5);
    EXPECT_NEAR(normal_upper_quantile(0.5), 0.0, 1e-9);
}

namespace {

// A synthetic run: N paths, each leaving with probability `exit` through bin b (probability p_b among exits) with a
// weight k / 4096, k uniform in [2048, 6144] (mean exactly 1, on the fixed-point grid: no rounding), the same in
// R and G and half of it in B. Returns the run and the exact bin averages of f.
struct Synthetic {
    SimResult run;
    std::vector<glm::dvec3> truth;
};

Synthetic synthetic_run(uint64_t seed, uint64_t paths) {
    Synthetic s;
    SimResult& r = s.run;
    r.stack = make_stack("synthetic", {dielectric(1.5f), lambertian(glm::vec3(0.5f))});
    r.options.dtheta_deg = 10;
    r.options.dphi_deg = 30;
    r.n_theta = 9;
    r.n_phi = 12;
    r.n_sides = 1;
    r.n_classes = 1;
    const size_t nb = size_t(r.n_theta) * r.n_phi;
    // a lobe near theta 30, phi 0 over a floor, down to a few paths per bin at grazing: exercises the pooling
    std::vector<double> p(nb);
    double total = 0;
    for (uint32_t t = 0; t < r.n_theta; ++t)
        for (uint32_t q = 0; q < r.n_phi; ++q) {
            double th = (t + 0.5) * 10, ph = q * 30.0;
            double v = 0.02 + std::exp(-std::pow((th - 30) / 15, 2) - std::pow(std::min(ph, 360 - ph) / 40, 2));
            v *= std::cos(th * M_PI / 180);
            p[t * r.n_phi + q] = v;
            total += v;
        }
    const double exit = 0.6;
    std::discrete_distribution<size_t> bin(p.begin(), p.end());
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint64_t> k(2048, 6144);
    std::bernoulli_distribution leaves(exit);
    AngleResult a;
    a.paths = paths;
    a.raw.assign(nb * 6, 0);
    for (uint64_t i = 0; i < paths; ++i) {
        if (!leaves(rng)) continue;
        const size_t b = bin(rng);
        const uint64_t w = k(rng);   // weight w / 4096; the raw sums are in units of 2^-12
        const uint64_t wb = w / 2;   // blue: half (w even or odd: floor, exactly representable)
        a.raw[b * 6 + 0] += w;
        a.raw[b * 6 + 1] += w;
        a.raw[b * 6 + 2] += wb;
        a.raw[b * 6 + 3] += w * w / 4096;   // (w / 4096)^2 in units of 2^-12, truncated: under 1e-3 of it
        a.raw[b * 6 + 4] += w * w / 4096;
        a.raw[b * 6 + 5] += wb * wb / 4096;
    }
    r.angles.push_back(a);
    r.options.theta_i_deg = {0.0};
    // the exact mean of w / 4096 is 1; of floor(w / 2) / 4096, computed here
    double blue = 0;
    for (uint64_t w = 2048; w <= 6144; ++w) blue += double(w / 2);
    blue /= 4097.0 * 4096.0;
    BinGrid g(r);
    s.truth.resize(nb);
    for (uint32_t t = 0; t < r.n_theta; ++t)
        for (uint32_t q = 0; q < r.n_phi; ++q) {
            const size_t b = t * r.n_phi + q;
            const double mean = exit * p[b] / total;   // expected share of paths through the bin
            s.truth[b] = glm::dvec3(mean, mean, mean * blue) / g.projected_solid_angle(t);
        }
    return s;
}

}   // namespace

// The fit's log residual takes the reference's remapped value corrected for the curvature of g(f) = log(1 + sqrt f):
// over a normal spread of estimates f_hat (se 5% of f, the cells' threshold, and 15%), the mean of g(f_hat) is below
// g(f) by about -g''(f) se^2 / 2, and the mean of remapped_unbiased(f_hat, se) is g(f) to a tenth of that.
TEST(Remapped, TheCorrectionRemovesTheCurvaturesBias) {
    for (double f : {0.02, 0.3, 2.0, 30.0})
        for (double rse : {0.05, 0.15}) {
            const double se = rse * f;
            double plain = 0, corrected = 0, weight = 0;
            for (int i = -3000; i <= 3000; ++i) {   // the normal density on +-6 se, midpoint rule
                const double x = i / 500.0, w = std::exp(-0.5 * x * x), fh = f + x * se;
                plain += w * gonio::remapped(fh);
                corrected += w * gonio::remapped_unbiased(fh, se);
                weight += w;
            }
            plain = plain / weight - gonio::remapped(f);
            corrected = corrected / weight - gonio::remapped(f);
            EXPECT_LT(plain, 0) << f << " " << rse;   // g is concave: noise pulls it down
            EXPECT_LT(std::fabs(corrected), 0.1 * std::fabs(plain)) << f << " " << rse << ": " << plain;
        }
}

// The Comparison (host/run/comparison.h), what every printer reads: each scored model's metrics are compare_model's
// with its integration error, a model that is not scored has none, the best model is the one of least RMSE and the
// runner-up the next (told apart here: a 5% bias at 2e5 paths), the total albedo is the reflected one (one side) and
// the largest its largest channel.
TEST(Verdict, TheComparisonIsComputedOnceAsCompareModelComputesIt) {
    const Synthetic s = synthetic_run(7, 200000);
    std::vector<ModelSlices> models(3);
    models[0].id = "biased";
    models[1].id = "exact";
    models[2].id = "not-applicable";
    models[0].f = {s.truth};
    for (auto& v : models[0].f[0]) v *= 1.05;
    models[1].f = {s.truth};
    models[1].f_err = {std::vector<glm::dvec3>(s.truth.size(), glm::dvec3(1e-9))};
    models[2].not_applicable = "a reason";
    const Comparison c = compare_models(s.run, models);
    ASSERT_EQ(c.models.size(), 3u);
    EXPECT_TRUE(c.models[2].r.empty() && c.models[2].total_albedo.empty());
    for (size_t m = 0; m < 2; ++m) {
        ASSERT_EQ(c.models[m].r.size(), 1u);
        EXPECT_TRUE(c.models[m].t.empty());
        const ModelMetrics direct =
            compare_model(s.run, 0, models[m].f[0], kReflection, m == 1 ? &models[1].f_err[0] : nullptr);
        EXPECT_EQ(c.models[m].r[0].rmse_remapped, direct.rmse_remapped) << models[m].id;
        EXPECT_EQ(c.models[m].r[0].agreement.chi2_per_dof, direct.agreement.chi2_per_dof) << models[m].id;
        EXPECT_EQ(c.models[m].r[0].agreement.integration_error_over_noise,
                  direct.agreement.integration_error_over_noise)
            << models[m].id;
        EXPECT_EQ(c.models[m].total_albedo[0], direct.albedo_model) << models[m].id;
        const glm::dvec3 a = direct.albedo_model;
        EXPECT_EQ(c.models[m].largest.value, std::max({a.x, a.y, a.z})) << models[m].id;
    }
    EXPECT_GE(c.models[1].r[0].agreement.integration_error_over_noise, 0.0);   // the error was passed
    const BestModel& b = c.best_of(0, kReflection);
    EXPECT_EQ(b.best, "exact");
    EXPECT_EQ(b.runner_up, "biased");
    EXPECT_FALSE(b.tie) << b.separation_z;
    EXPECT_TRUE(c.best_of(0, kTransmission).best.empty());   // a one-sided run has no transmission slice
}

TEST(Verdict, SyntheticRunsAreRejectedAtTheNominalRateAndBiasesAreSeen) {
    const int trials = 400;
    int rejected_exact = 0, rejected_bias = 0, rejected_shape = 0;
    double chi2_sum = 0;
    for (int i = 0; i < trials; ++i) {
        Synthetic s = synthetic_run(1000 + i, 20000);
        const Agreement exact = compare_model(s.run, 0, s.truth).agreement;
        rejected_exact += !exact.within_noise;
        chi2_sum += exact.chi2_per_dof;
        std::vector<glm::dvec3> biased = s.truth, shaped = s.truth;
        for (auto& v : biased) v *= 1.05;
        for (size_t b = 0; b < shaped.size(); ++b) shaped[b] *= (b / 12) % 2 ? 1.1 : 0.9;
        rejected_bias += !compare_model(s.run, 0, biased).agreement.within_noise;
        const Agreement sh = compare_model(s.run, 0, shaped).agreement;
        rejected_shape += !sh.within_noise;
    }
    std::printf("exact model rejected %d/%d, mean chi2/dof %.4f; 5%% bias rejected %d/%d; +-10%% rows rejected %d/%d\n",
                rejected_exact, trials, chi2_sum / trials, rejected_bias, trials, rejected_shape, trials);
    // two tests at 1% with Bonferroni over the channels: at most 2% of exact models are rejected (4% allowed for
    // the trials' own noise: P(more than 16 of 400 at 2%) < 0.5%)
    EXPECT_LE(rejected_exact, trials * 4 / 100);
    EXPECT_NEAR(chi2_sum / trials, 1.0, 0.05);
    EXPECT_GE(rejected_bias, trials * 9 / 10);
    EXPECT_GE(rejected_shape, trials * 9 / 10);
}

TEST(Verdict, TheSmallestDetectableBiasIsWhatTheBiasTestSees) {
    Synthetic s = synthetic_run(7, 200000);
    const Agreement exact = compare_model(s.run, 0, s.truth).agreement;
    ASSERT_TRUE(exact.within_noise) << exact.reason;
    ASSERT_GT(exact.smallest_detectable_relative_bias, 0.0);
    std::vector<glm::dvec3> off = s.truth;
    for (auto& v : off) v *= 1 + 3 * exact.smallest_detectable_relative_bias;
    const Agreement a = compare_model(s.run, 0, off).agreement;
    EXPECT_FALSE(a.within_noise);
    EXPECT_LT(a.bias_p_value, kVerdictLevel);
    EXPECT_GT(a.mean_z, 0.0);   // the model is above the reference: a positive bias
}

class VerdictOnTheDevice : public GpuTest {};

TEST_F(VerdictOnTheDevice, AnExactModelIsWithinTheNoiseAndAScaledOneIsNot) {
    // over a black base the reference traces the rough coat's single-scattering reflection, which ww-corrected's
    // top term is (the reference's own interface BRDF; tests/test_models.cpp BlackBaseLeavesTheTopReflection)
    const Stack s = make_stack("black-base", {dielectric(1.5f, 0.3f), lambertian(glm::vec3(0.0f))});
    size_t wwc = 0;
    while (model_registry()[wwc].id != "ww-corrected") ++wwc;
    SimOptions o;
    o.theta_i_deg = {0, 30, 60, 80};
    o.paths = 4000000;
    for (uint32_t seed = 1; seed <= 2; ++seed) {
        o.seed = seed;
        const SimResult r = simulate_gpu(context(), s, o);
        const std::vector<ModelSlices> ms = evaluate_models(context(), s, model_grid(r));
        for (size_t a = 0; a < r.angles.size(); ++a) {
            const Agreement ag = compare_model(r, a, ms[wwc].f[a]).agreement;
            std::printf(
                "seed %u theta_i %g: chi2/dof %.3f mean z %+.3f p %.3g / %.3g, %llu single bins, %llu cells pooled\n",
                seed, o.theta_i_deg[a], ag.chi2_per_dof, ag.mean_z, ag.chi2_p_value, ag.bias_p_value,
                (unsigned long long)ag.cells, (unsigned long long)ag.pooled_cells);
            EXPECT_TRUE(ag.within_noise) << "seed " << seed << " theta_i " << o.theta_i_deg[a] << ": " << ag.reason;
            EXPECT_NEAR(ag.chi2_per_dof, 1.0, 0.2);
            std::vector<glm::dvec3> off = ms[wwc].f[a];
            for (auto& v : off) v *= 1 + 3 * ag.smallest_detectable_relative_bias;
            EXPECT_FALSE(compare_model(r, a, off).agreement.within_noise) << "theta_i " << o.theta_i_deg[a];
        }
    }
}
