// The Lambertian series (host/core/lambertian_series.h, shaders/lib/walk.glsl): its quadrature against the closed form
// of a smooth coat and against itself refined, and the walk that uses it against the walk that traces every trip
// (independent seeds), band by band and in total energy, on the stacks where it is hardest (near-smooth, very rough,
// very absorbing, rarer-than-exterior and index-matched coats; grazing light).
#include "exact.h"
#include "gpu_fixture.h"
#include "lambertian_series.h"
#include "stack_gpu.h"

#include <cstdio>

using namespace gonio;
using namespace gonio_test;

namespace {

// exact one-trip integrals of a smooth coat of index n (exterior n0, optical depth tau): per unit energy leaving
// the base with the cosine density, escaped = int 2 mu exp(-tau/mu) (1 - F(mu)) dmu, returned with exp(-2 tau/mu) F
SeriesTrip smooth_trip(double n0, double n, double tau) {
    const int N = 400000;
    SeriesTrip t;
    for (int i = 0; i < N; ++i) {
        double mu = (i + 0.5) / N, F = exact::fresnel(mu, n, n0);
        t.escaped += glm::dvec3(2 * mu * std::exp(-tau / mu) * (1 - F) / N);
        t.returned += glm::dvec3(2 * mu * std::exp(-2 * tau / mu) * F / N);
    }
    return t;
}

std::vector<Stack> series_stacks() {
    std::vector<Stack> v;
    v.push_back(parse_stack_file(GONIO_SOURCE_DIR "/stacks/plastic.toml"));
    v.push_back(parse_stack_file(GONIO_SOURCE_DIR "/stacks/hard/roughness-1-lambertian.toml"));
    v.push_back(parse_stack_file(GONIO_SOURCE_DIR "/stacks/hard/optical-depth-50.toml"));
    v.push_back(make_stack("near-smooth", {dielectric(1.5f, 1e-4f, glm::vec3(0.0f, 0.2f, 1.0f)),
                                           lambertian(glm::vec3(0.9f, 0.5f, 0.1f))}));
    v.push_back(make_stack("rarer-coat", {dielectric(1.2f, 0.1f, glm::vec3(0.1f)), lambertian(glm::vec3(0.8f))}, 2.0f));
    v.push_back(make_stack("matched-coat", {dielectric(1.0f, 0.3f, glm::vec3(0.3f)), lambertian(glm::vec3(0.7f))}));
    return v;
}

}   // namespace

TEST(LambertianSeries, SmoothCoatTripMatchesClosedForm) {
    struct Case {
        double n0, n, tau;
    };
    for (Case c :
         {Case{1.0, 1.5, 0.0}, Case{1.0, 1.5, 0.3}, Case{1.0, 3.0, 1.0}, Case{2.0, 1.3, 0.1}, Case{1.0, 1.5, 50.0}}) {
        Stack s =
            make_stack("smooth", {dielectric(float(c.n), 0.0f, glm::vec3(float(c.tau))), lambertian(glm::vec3(0.5f))},
                       float(c.n0));
        SeriesTrip q = lambertian_trip(pack_stack(s)), e = smooth_trip(c.n0, c.n, c.tau);
        std::printf("n0 %.1f n %.1f tau %.1f: escaped %.8f (exact %.8f), returned %.8f (exact %.8f), lost %.2e\n", c.n0,
                    c.n, c.tau, q.escaped.x, e.escaped.x, q.returned.x, e.returned.x, q.lost.x);
        EXPECT_NEAR(q.escaped.x, e.escaped.x, 2e-6);
        EXPECT_NEAR(q.returned.x, e.returned.x, 2e-6);
        EXPECT_NEAR(q.lost.x, 0.0, 1e-7);   // a smooth interface loses nothing
    }
}

// The quadrature's error estimate is honest: the terms the series uses are within their estimated error of a rule
// with 2.5 times the nodes in every dimension, and the relative error bound it implies stays below 1e-4.
TEST(LambertianSeries, QuadratureErrorEstimateHolds) {
    for (const Stack& s : series_stacks()) {
        LambertianSeries ls = lambertian_series(pack_stack(s));
        ASSERT_TRUE(ls.applies) << s.name << ": " << ls.reason;
        if (s.layers[0].roughness == 0.0f || s.layers[0].optical_depth.x > 10.0f)
            continue;   // trivial; keeps the test short
        SeriesTrip fine = lambertian_trip(pack_stack(s), 2.5);
        double d = 0.0;
        for (int c = 0; c < 3; ++c)
            d = std::max({d, std::fabs(fine.escaped[c] - ls.trip.escaped[c]),
                          std::fabs(fine.returned[c] - ls.trip.returned[c]),
                          std::fabs(fine.lost[c] - ls.trip.lost[c])});
        std::printf(
            "%-24s escaped %.7f returned %.7f lost %.7f S %.4f: finer rule differs by %.1e, estimate %.1e, "
            "relative bound %.1e\n",
            s.name.c_str(), ls.trip.escaped.x, ls.trip.returned.x, ls.trip.lost.x, ls.gain.x, d, ls.quadrature_error,
            ls.relative_error);
        EXPECT_LE(d, ls.quadrature_error) << s.name;
        EXPECT_LT(ls.relative_error, kMaxSeriesRelativeError) << s.name;
        for (int c = 0; c < 3; ++c)   // a trip's energy: escaped, returned, lost, and absorbed on the way (>= 0)
            EXPECT_LE(ls.trip.escaped[c] + ls.trip.returned[c] + ls.trip.lost[c], 1.0 + 1e-6) << s.name;
    }
}

TEST(LambertianSeries, AppliesOnlyWhereItIsExact) {
    EXPECT_FALSE(
        lambertian_series(pack_stack(parse_stack_file(GONIO_SOURCE_DIR "/stacks/metallic-paint.toml"))).applies);
    EXPECT_FALSE(lambertian_series(pack_stack(parse_stack_file(GONIO_SOURCE_DIR "/stacks/hard/index-matched.toml")))
                     .applies);   // 3 layers
    // IOR 3 over a white base: the coat returns 83% of the light (S = 5.9), which magnifies the quadrature's error
    // beyond the bound: the walk traces every trip there
    LambertianSeries ior3 = lambertian_series(pack_stack(parse_stack_file(GONIO_SOURCE_DIR "/stacks/hard/ior-3.toml")));
    EXPECT_FALSE(ior3.applies);
    EXPECT_NE(ior3.reason.find("quadrature"), std::string::npos) << ior3.reason;
    Stack plastic = parse_stack_file(GONIO_SOURCE_DIR "/stacks/plastic.toml");
    EXPECT_TRUE(walk_spec(plastic, true).series);
    EXPECT_FALSE(walk_spec(plastic, false).series);   // the general walk
    EXPECT_FALSE(walk_spec(plastic, true, false).series);   // --no-series
    EXPECT_FALSE(walk_spec(plastic, true, true, true).series);   // --orders: classes need every trip
    EXPECT_FALSE(walk_spec(plastic, true, true, false, 2).series);   // room for 3 events
    // a lossless coat that traps nearly everything over a white base: the exits would weigh too much
    Stack trap = make_stack("trap", {dielectric(10.0f, 0.0f), lambertian(glm::vec3(1.0f))});
    LambertianSeries t = lambertian_series(pack_stack(trap));
    EXPECT_FALSE(t.applies);
    EXPECT_FALSE(t.reason.empty());
    // a coat whose medium scatters, then the same coat clear: the memo keeps them apart (its key holds no scattering)
    Stack hazy = plastic;
    hazy.layers[0].scattering_albedo = glm::vec3(0.5f);
    EXPECT_FALSE(lambertian_series(pack_stack(hazy)).applies);
    EXPECT_TRUE(lambertian_series(pack_stack(plastic)).applies);
    Stack clear = plastic;
    clear.name = "clear-first";
    EXPECT_TRUE(lambertian_series(pack_stack(clear)).applies);
    EXPECT_FALSE(lambertian_series(pack_stack(hazy)).applies);
}

namespace {

// Per-path mean and standard error of the energy leaving through `side` within theta bands of `band` bins, from the
// raw sums (each path lands in one bin at most, so the band's per-path variance comes from its sums of squares).
struct Band {
    double mean[3], se[3];
};
std::vector<Band> bands(const SimResult& r, const AngleResult& a, int side, uint32_t band) {
    std::vector<Band> out((r.n_theta + band - 1) / band, Band{});
    std::vector<std::array<double, 6>> sums(out.size(), std::array<double, 6>{});
    for (uint32_t t = 0; t < r.n_theta; ++t)
        for (uint32_t p = 0; p < r.n_phi; ++p) {
            size_t b = ((size_t(side) * r.n_theta + t) * r.n_phi + p) * 6;
            for (int k = 0; k < 6; ++k) sums[t / band][k] += double(a.raw[b + k]) / kFixedScale;
        }
    const double N = double(a.paths);
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double m = sums[i][c] / N, m2 = sums[i][3 + c] / N;
            out[i].mean[c] = m;
            out[i].se[c] = std::sqrt(std::max(0.0, m2 - m * m) / N);
        }
    return out;
}

}   // namespace

class SeriesWalk : public GpuTest {};

// The series walk and the walk that traces every trip, on independent seeds: the energy in every 10-degree band of
// exit angles agrees within the standard errors (|z| < 4.5 over about 600 comparisons: a false alarm has probability
// below 0.5%), and so does the microfacet loss (the series books its expectation; bound on its standard error: a
// path's loss l is at most l_max, so var l <= l_max E[l]).
TEST_F(SeriesWalk, AgreesWithTheFullWalk) {
    SimOptions o;
    o.theta_i_deg = {0.0, 60.0, 85.0};
    o.paths = 2000000;
    int compared = 0;
    double worst = 0;
    for (const Stack& s : series_stacks()) {
        SimOptions os = o, of = o;
        os.seed = 3;
        of.seed = 4;
        of.series = false;
        ASSERT_TRUE(walk_spec(s, true).series) << s.name;
        SimResult rs = simulate_gpu(context(), s, os), rf = simulate_gpu(context(), s, of);
        for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
            auto bs = bands(rs, rs.angles[a], 0, 10), bf = bands(rf, rf.angles[a], 0, 10);
            for (size_t i = 0; i < bs.size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    double se = std::hypot(bs[i].se[c], bf[i].se[c]);
                    if (se == 0) {
                        EXPECT_EQ(bs[i].mean[c], bf[i].mean[c]);
                        continue;
                    }
                    double z = (bs[i].mean[c] - bf[i].mean[c]) / se;
                    compared++;
                    worst = std::max(worst, std::fabs(z));
                    EXPECT_LT(std::fabs(z), 4.5)
                        << s.name << " theta_i " << o.theta_i_deg[a] << " band " << i << " channel " << c << ": series "
                        << bs[i].mean[c] << " +- " << bs[i].se[c] << ", full walk " << bf[i].mean[c] << " +- "
                        << bf[i].se[c];
                }
            // nothing is truncated by the series
            const LambertianSeries ls = lambertian_series(pack_stack(s));
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(rs.angles[a].energy[6 + c], 0) << s.name;
                const double N = double(o.paths);
                double ls_ = double(rs.angles[a].energy[3 + c]) / kEnergyScale / N,
                       lf = double(rf.angles[a].energy[3 + c]) / kEnergyScale / N;
                double lmax = std::max(1.0, ls.max_weight * ls.lost_all[c]);
                double se = std::sqrt((lmax * ls_ + lf) / N);
                EXPECT_LT(std::fabs(ls_ - lf), 4.5 * se + 1e-9)
                    << s.name << " theta_i " << o.theta_i_deg[a] << " microfacet loss, channel " << c;
            }
        }
    }
    std::printf("%d band-channels compared, largest |z| %.2f\n", compared, worst);
}
