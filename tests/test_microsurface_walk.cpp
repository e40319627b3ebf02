// The walk on a rough interface whose microsurface is not GGX with height-correlated Smith (a stack's `distribution`
// and `shadowing`; shaders/lib/microsurface.glsl): a conductor of F = 1 (n 0.01, k 100: F within 4e-6 of 1) reflects
// the single-scattering albedo that the BRDF's integral gives (microfacet_quadrature.h; its D and Lambda held against
// the projected area in test_microsurface.cpp), for Beckmann and GGX, height-correlated and separable; the specialised
// walk, the general walk and the CPU twin agree on a coat over a metal; and what the microsurface turns off (the
// Lambertian series) and the models that refuse it say why. With light walking on the microsurface (`microfacets =
// "multiple"`): the furnaces through the walk (R + T = 1, a conductor of F = 1 reflects 1, nothing lost), and the
// three walks agree on a coat over a metal, above what single scattering reflects.
#include "compat.glsl"
#include "gpu_fixture.h"
#include "microfacet_quadrature.h"
#include "microsurface.glsl"
#include "model_applicability.h"
#include "model_registry.h"
#include "json.h"
#include "output.h"
#include "state.h"
#include "stack_gpu.h"

#include <cstdio>
#include <filesystem>
#include <string>

using namespace gonio;
using namespace gonio_test;

namespace {

Layer with_microsurface(Layer y, MicrofacetDistribution d, Shadowing g) {
    y.distribution = d;
    y.shadowing = g;
    return y;
}

uint micro_of(MicrofacetDistribution d, Shadowing g) {
    return (d == MicrofacetDistribution::Beckmann ? MICROSURFACE_BECKMANN : 0u) |
           (g == Shadowing::Separable ? MICROSURFACE_SEPARABLE : 0u);
}

// The albedo with F = 1: the integral over the microfacets h of G2(wi, wo) (wi.h) / wi.z, wo the mirror of wi about h
// (f cos dwo = D G2 / (4 wi.z) 4 (wi.h) dh), G2 height-correlated or separable.
double albedo_by_quadrature(glm::vec3 wi, float alpha, uint micro) {
    auto D = [micro](vec3 m, float a) { return (micro & MICROSURFACE_BECKMANN) ? beckmann_D(m, a) : ggx_D(m, a); };
    const float li = microsurface_lambda(wi, alpha, micro);
    return microfacet_quadrature::over_microfacets(
        alpha, D,
        [&](glm::vec3 h) {
            const float c = dot(wi, h);
            const vec3 wo = 2.0f * c * h - wi;
            if (c <= 0.0f || wo.z <= 0.0f) return 0.0;
            const double lo = microsurface_lambda(wo, alpha, micro);
            const double g2 =
                (micro & MICROSURFACE_SEPARABLE) ? 1.0 / ((1.0 + li) * (1.0 + lo)) : 1.0 / (1.0 + li + lo);
            return g2 * c / wi.z;
        },
        1000, 360);
}

// The fraction of the light that leaves (all bins, channel 0) at angle a, from the run's raw sums.
double exit_fraction(const SimResult& r, size_t a) {
    const AngleResult& ar = r.angles[a];
    double s1 = 0.0;
    for (size_t b = 0; b + 5 < ar.raw.size(); b += 6) s1 += double(ar.raw[b]) / kFixedScale;
    return s1 / double(ar.paths);
}

// The stack under the specialised walk and the general walk (o's paths) and the CPU twin (a quarter of them)
struct ThreeWalks {
    SimResult spec, general, twin;
};
ThreeWalks three_walks(const Stack& s, const SimOptions& o) {
    SimOptions g = o, c = o;
    g.specialised = false;
    c.paths = o.paths / 4;
    return {simulate_gpu(context(), s, o), simulate_gpu(context(), s, g), simulate_cpu(s, c, 2)};
}

class MicrosurfaceWalk : public GpuTest {};

TEST_F(MicrosurfaceWalk, ConductorAlbedoIsTheIntegralOfItsBrdf) {
    struct Case {
        MicrofacetDistribution d;
        Shadowing g;
    };
    const Case cases[] = {{MicrofacetDistribution::Beckmann, Shadowing::HeightCorrelated},
                          {MicrofacetDistribution::Beckmann, Shadowing::Separable},
                          {MicrofacetDistribution::Ggx, Shadowing::Separable},
                          {MicrofacetDistribution::Ggx, Shadowing::HeightCorrelated}};
    for (const Case& c : cases)
        for (float alpha : {0.3f, 1.0f}) {
            const Stack s = make_stack(
                "metal", {with_microsurface(conductor(glm::vec3(0.01f), glm::vec3(100.0f), alpha), c.d, c.g)});
            SimOptions o;
            o.theta_i_deg = {0, 45, 75};
            o.paths = 1000000;
            const SimResult r = simulate_gpu(context(), s, o);
            for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
                const double t = o.theta_i_deg[a] * M_PI / 180;
                const glm::vec3 wi(float(std::sin(t)), 0.0f, float(std::cos(t)));
                const double expected = albedo_by_quadrature(wi, alpha, micro_of(c.d, c.g));
                const double got = exit_fraction(r, a);
                const double se = exit_fraction_se(r, a, 0);
                std::printf("%s %s alpha %.1f theta %2.0f: walk %.6f +- %.6f, integral %.6f\n",
                            c.d == MicrofacetDistribution::Beckmann ? "beckmann" : "ggx     ",
                            c.g == Shadowing::Separable ? "separable        " : "height-correlated", alpha,
                            o.theta_i_deg[a], got, se, expected);
                EXPECT_LT(std::abs(got - expected), 4 * se + 1e-4)
                    << "alpha " << alpha << " theta " << o.theta_i_deg[a];
            }
        }
}

// A Beckmann coat (separable shadowing) over a rough Beckmann metal: the specialised walk (with its booking
// estimators), the general walk and the CPU twin reflect the same energy within their noise.
TEST_F(MicrosurfaceWalk, SpecialisedGeneralAndCpuTwinAgree) {
    const Stack s =
        make_stack("coated metal",
                   {with_microsurface(dielectric(1.5f, 0.4f), MicrofacetDistribution::Beckmann, Shadowing::Separable),
                    with_microsurface(conductor(glm::vec3(0.2f), glm::vec3(3.0f), 0.3f),
                                      MicrofacetDistribution::Beckmann, Shadowing::HeightCorrelated)});
    const WalkSpec ws = walk_spec(s, true);
    EXPECT_EQ(ws.microsurface_mask,
              (MICROSURFACE_BECKMANN | MICROSURFACE_SEPARABLE) | (MICROSURFACE_BECKMANN << MICROSURFACE_BITS));
    SimOptions o;
    o.theta_i_deg = {30, 70};
    o.paths = 400000;
    const auto [spec, general, twin] = three_walks(s, o);
    const int bookings = 1 + (ws.entry_branch ? 1 : 0) + int(ws.exit_estimates);
    for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
        auto reflected = [a](const SimResult& r) { return exit_fraction(r, a); };
        const double s1 = exit_fraction_se_bound(spec, a, 0, bookings), s2 = exit_fraction_se(general, a, 0),
                     s3 = exit_fraction_se_bound(twin, a, 0, bookings);
        std::printf("theta %.0f: specialised %.5f +- %.5f, general %.5f +- %.5f, CPU twin %.5f +- %.5f\n",
                    o.theta_i_deg[a], reflected(spec), s1, reflected(general), s2, reflected(twin), s3);
        EXPECT_LT(std::abs(reflected(spec) - reflected(general)), 4 * std::hypot(s1, s2));
        EXPECT_LT(std::abs(reflected(spec) - reflected(twin)), 4 * std::hypot(s1, s3));
    }
    // summary.json's walk names the interfaces' microsurfaces, and a state file keeps them
    const auto dir = std::filesystem::temp_directory_path() / "gonio_test_microsurface";
    std::filesystem::create_directories(dir);
    save_state((dir / "state.gonio").string(), spec);
    write_summary_json((dir / "summary.json").string(), load_state((dir / "state.gonio").string()));
    const Json micro = read_json_file((dir / "summary.json").string())["walk"]["microsurfaces"];
    ASSERT_EQ(micro.size(), 2u);
    EXPECT_EQ(micro[0]["distribution"], "beckmann");
    EXPECT_EQ(micro[0]["shadowing"], "separable");
    EXPECT_EQ(micro[1]["layer"], 2);
    EXPECT_EQ(micro[1]["shadowing"], "height-correlated");
    // and differ from the GGX stack's by more than that: the walk reads the microsurface
    Stack ggx = s;
    for (Layer& y : ggx.layers) y.distribution = MicrofacetDistribution::Ggx;
    const SimResult other = simulate_gpu(context(), ggx, o);
    EXPECT_GT(std::abs(exit_fraction(other, 1) - exit_fraction(spec, 1)),
              10 * exit_fraction_se_bound(spec, 1, 0, bookings));
}

Layer walking_on_microsurface(Layer y, MicrofacetDistribution d) {
    y.distribution = d;
    y.microfacets = Microfacets::Multiple;
    return y;
}

// The light that the walk booked as lost (channel 0) at angle a: with light walking on the microsurface, only what is
// still on it after MICROSURFACE_MAX_MEETINGS meetings.
double lost_fraction(const SimResult& r, size_t a) {
    return double(r.angles[a].energy[3]) / double(kEnergyScale) / double(r.angles[a].paths);
}

// Light walking on the microsurface (`microfacets = "multiple"`; microsurface_walk.glsl) through the walk: a
// non-absorbing rough dielectric interface lets everything through or back (R + T = 1 within 1e-4) and a conductor of
// F = 1 (n 0.01, k 100: 1 - F below 1e-4 on every facet) reflects everything but its Fresnel leak, alpha 1, GGX and
// Beckmann, to 89 degrees; nothing is lost.
TEST_F(MicrosurfaceWalk, MultipleScatteringFurnaces) {
    for (MicrofacetDistribution d : {MicrofacetDistribution::Ggx, MicrofacetDistribution::Beckmann}) {
        const Stack interface = make_stack("interface", {walking_on_microsurface(dielectric(1.5f, 1.0f), d)});
        const Stack metal =
            make_stack("metal", {walking_on_microsurface(conductor(glm::vec3(0.01f), glm::vec3(100.0f), 1.0f), d)});
        SimOptions o;
        o.theta_i_deg = {0, 45, 75, 89};
        o.paths = 200000;
        const SimResult ri = simulate_gpu(context(), interface, o), rm = simulate_gpu(context(), metal, o);
        for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
            std::printf("%s theta %2.0f: interface R + T %.7f lost %.2g, metal albedo %.7f lost %.2g\n",
                        d == MicrofacetDistribution::Ggx ? "ggx     " : "beckmann", o.theta_i_deg[a],
                        exit_fraction(ri, a), lost_fraction(ri, a), exit_fraction(rm, a), lost_fraction(rm, a));
            EXPECT_NEAR(exit_fraction(ri, a), 1.0, 1e-4) << "theta " << o.theta_i_deg[a];
            EXPECT_LT(lost_fraction(ri, a), 1e-4);
            EXPECT_NEAR(exit_fraction(rm, a), 1.0, 1e-4) << "theta " << o.theta_i_deg[a];
            EXPECT_LT(lost_fraction(rm, a), 1e-4);
        }
    }
}

// A coat walking on its GGX microsurface over a metal walking on its Beckmann one: the specialised walk (without the
// booking estimators, which sample single scattering), the general walk and the CPU twin reflect the same energy, and
// more than the same stack scattering once; summary.json and the state file record it.
TEST_F(MicrosurfaceWalk, MultipleScatteringSpecialisedGeneralAndCpuTwinAgree) {
    const Stack s = make_stack(
        "coated metal",
        {walking_on_microsurface(dielectric(1.5f, 0.5f), MicrofacetDistribution::Ggx),
         walking_on_microsurface(conductor(glm::vec3(0.2f), glm::vec3(3.0f), 0.6f), MicrofacetDistribution::Beckmann)});
    const WalkSpec ws = walk_spec(s, true);
    EXPECT_EQ(ws.multiple_mask, 3u);
    EXPECT_EQ(ws.microsurface_mask, MICROSURFACE_BECKMANN << MICROSURFACE_BITS);
    EXPECT_FALSE(ws.entry_branch);
    EXPECT_EQ(ws.exit_estimates, 0u);
    SimOptions o;
    o.theta_i_deg = {30, 70};
    o.paths = 400000;
    const auto [spec, general, twin] = three_walks(s, o);
    for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
        const double s1 = exit_fraction_se(spec, a, 0), s2 = exit_fraction_se(general, a, 0),
                     s3 = exit_fraction_se(twin, a, 0);
        std::printf("multiple, theta %.0f: specialised %.5f +- %.5f, general %.5f +- %.5f, CPU twin %.5f +- %.5f\n",
                    o.theta_i_deg[a], exit_fraction(spec, a), s1, exit_fraction(general, a), s2, exit_fraction(twin, a),
                    s3);
        EXPECT_LT(std::abs(exit_fraction(spec, a) - exit_fraction(general, a)), 4 * std::hypot(s1, s2));
        EXPECT_LT(std::abs(exit_fraction(spec, a) - exit_fraction(twin, a)), 4 * std::hypot(s1, s3));
        EXPECT_LT(lost_fraction(spec, a), 1e-4);
    }
    Stack single = s;
    for (Layer& y : single.layers) y.microfacets = Microfacets::Single;
    const SimResult once = simulate_gpu(context(), single, o);
    for (size_t a = 0; a < o.theta_i_deg.size(); ++a)
        EXPECT_GT(exit_fraction(spec, a) - exit_fraction(once, a), 10 * exit_fraction_se(spec, a, 0));
    const auto dir = std::filesystem::temp_directory_path() / "gonio_test_multiple_scattering";
    std::filesystem::create_directories(dir);
    save_state((dir / "state.gonio").string(), spec);
    write_summary_json((dir / "summary.json").string(), load_state((dir / "state.gonio").string()));
    const Json micro = read_json_file((dir / "summary.json").string())["walk"]["microsurfaces"];
    ASSERT_EQ(micro.size(), 2u);
    EXPECT_EQ(micro[0]["microfacets"], "multiple");
    EXPECT_EQ(micro[0]["distribution"], "ggx");
    EXPECT_EQ(micro[1]["distribution"], "beckmann");
    EXPECT_EQ(micro[1]["microfacets"], "multiple");
}

// What a Beckmann interface turns off, with its reason: the Lambertian series (its trips' quadrature is GGX's) and
// every model (each reads roughness as a GGX alpha). Separable shadowing alone keeps the models.
TEST(MicrosurfaceStack, SeriesAndModelsSayWhy) {
    const Stack beckmann = make_stack(
        "coated diffuse",
        {with_microsurface(dielectric(1.5f, 0.05f), MicrofacetDistribution::Beckmann, Shadowing::HeightCorrelated),
         lambertian(glm::vec3(0.5f))});
    const WalkStack w = walk_stack(beckmann, true);
    EXPECT_FALSE(w.spec.series);
    EXPECT_NE(w.series.reason.find("not GGX with height-correlated Smith"), std::string::npos) << w.series.reason;
    const WalkStack g = walk_stack(make_stack("ggx", {dielectric(1.5f, 0.05f), lambertian(glm::vec3(0.5f))}), true);
    EXPECT_TRUE(g.spec.series) << g.series.reason;
    Stack separable = beckmann;
    separable.layers[0].distribution = MicrofacetDistribution::Ggx;
    separable.layers[0].shadowing = Shadowing::Separable;
    size_t represented = 0;
    for (size_t m = 0; m < model_registry().size(); ++m) {
        const std::string why = model_cannot_represent(m, beckmann);
        EXPECT_NE(why.find("takes GGX microfacets"), std::string::npos) << model_registry()[m].id << ": " << why;
        represented += model_cannot_represent(m, separable).empty();
    }
    EXPECT_GT(represented, 0u) << "separable shadowing alone refuses no model";
}

}   // namespace
