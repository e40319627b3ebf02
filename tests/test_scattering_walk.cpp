// The walk through scattering media (shaders/lib/walk.glsl, walk_medium_event) against exact answers, on the
// device (lavapipe in CI, validation layer on) and on the CPU twin, bin by bin (tests/bin_check.h):
// - single scattering in a thin index-matched layer over a black base, RGB optical depth and albedo (the channel
//   balance of the free flight), the event cap isolating the paths that scatter once;
// - Chandrasekhar's semi-infinite isotropic medium, every order, RGB albedo (tests/exact_media.h);
// - white furnaces: a conservative medium over a white base, and a conservative milky slab, give back all the light;
// - the path class of a path scattered back in the medium (one reversal beneath the top).
#include "bin_check.h"
#include "cpu_twin.h"
#include "exact_media.h"
#include "medium.glsl"

#include <cstdio>
#include <fstream>

using namespace gonio;
using namespace gonio_test;

namespace {

Layer scattering_layer(float ior, glm::vec3 tau, glm::vec3 albedo, float g, float roughness = 0.0f) {
    Layer l = dielectric(ior, roughness, tau);
    l.scattering_albedo = albedo;
    l.phase_g = g;
    return l;
}

// The exact bin average (1/sr) of a BRDF f(wo) given in the global frame: K x K quadrature of f cos over the bin.
double bin_average(const BinGrid& g, uint32_t t, uint32_t p, const std::function<double(glm::dvec3)>& f, int K = 8) {
    double acc = 0;
    for (int u = 0; u < K; ++u)
        for (int v = 0; v < K; ++v) {
            double th = (g.theta_lo(t) + (u + 0.5) / K * g.dtheta_deg) * M_PI / 180;
            double ph = (g.phi_lo(p) + (v + 0.5) / K * g.dphi_deg) * M_PI / 180;
            glm::dvec3 wo(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
            acc += f(wo) * std::cos(th) * std::sin(th);
        }
    return acc * (g.dtheta_deg * M_PI / 180 / K) * (g.dphi_deg * M_PI / 180 / K) / g.projected_solid_angle(t);
}

std::string where(bool cpu) { return cpu ? "CPU twin" : "device"; }

// Single scattering: index-matched smooth top (nothing refracts or reflects there), a black Lambertian base, and
// max_events 3: the top, one collision, the top again. A path that collides twice is truncated at its third event,
// one that reaches the base dies there, so what leaves is exactly the single-scattering term
// f1 = omega p(cos) (1 - exp(-tau (1/mu_i + 1/mu_o))) / (mu_i + mu_o), per channel with its own tau and omega.
void single_scattering(bool cpu, bool general) {
    const glm::vec3 tau(0.2f, 0.5f, 1.0f), omega(0.9f, 0.6f, 0.3f);
    const float g = 0.6f;
    Stack s = make_stack("single", {scattering_layer(1.0f, tau, omega, g), lambertian(glm::vec3(0.0f))});
    SimOptions o;
    o.theta_i_deg = {30.5, 65.5};
    o.paths = cpu ? 2000000 : 6000000;
    o.dtheta_deg = 3;
    o.dphi_deg = 6;
    o.seed = 31;
    o.max_events = 3;
    o.specialised = !general;
    SimResult r = run(s, o, cpu);
    BinGrid grid(r);
    BinCheck check;
    for (size_t a = 0; a < r.angles.size(); ++a) {
        const double ti = o.theta_i_deg[a] * M_PI / 180;
        const glm::dvec3 wi(std::sin(ti), 0, std::cos(ti));
        Slice sl = make_slice(r, a, kReflection);
        auto exact = [&](uint32_t t, uint32_t p, int c) {
            return bin_average(grid, t, p, [&](glm::dvec3 wo) {
                double phase = phase_hg(float(glm::dot(-wi, wo)), g);
                return exact_media::single_scattering_brdf(wi.z, wo.z, phase, tau[c], omega[c]);
            });
        };
        compare_bins(check, sl, grid, o.paths, 3, exact, "theta_i " + std::to_string(o.theta_i_deg[a]),
                     std::max({omega.x, omega.y, omega.z}));
    }
    expect_matches(check, where(cpu) + (general ? " general walk" : "") + " single scattering, RGB tau and albedo");
}

// Every order in a semi-infinite isotropic medium (tau 1e3 over a black base, which no path reaches) under an
// index-matched smooth top: f = omega / (4 pi) H(mu_i) H(mu_o) / (mu_i + mu_o), Chandrasekhar's H per channel.
void semi_infinite(bool cpu) {
    const glm::vec3 omega(0.5f, 0.9f, 0.99f);
    Stack s = make_stack("semi-infinite",
                         {scattering_layer(1.0f, glm::vec3(1e3f), omega, 0.0f), lambertian(glm::vec3(0.0f))});
    SimOptions o;
    o.theta_i_deg = {0.5, 45.5, 75.5};
    o.paths = cpu ? 600000 : 3000000;
    o.dtheta_deg = 3;
    o.dphi_deg = 12;
    o.seed = 37;
    o.max_events = 4000;
    SimResult r = run(s, o, cpu);
    BinGrid grid(r);
    BinCheck check;
    std::vector<exact_media::HFunction> H;
    for (int c = 0; c < 3; ++c) H.emplace_back(double(omega[c]));
    for (size_t a = 0; a < r.angles.size(); ++a) {
        const double mu_i = std::cos(o.theta_i_deg[a] * M_PI / 180);
        const EnergyBook e = energy_book(r, a);
        for (int c = 0; c < 3; ++c) {
            EXPECT_LT(e.truncated[c], 1e-4) << "channel " << c << ": paths reach the event cap";
            // the directional albedo, 1 - H(mu_i) sqrt(1 - omega), to a few standard errors (weights below 1)
            const double albedo = 1 - H[c](mu_i) * std::sqrt(1 - double(omega[c]));
            EXPECT_NEAR(e.reflected[c], albedo, 5.0 / std::sqrt(double(o.paths)) + 1e-4)
                << where(cpu) << " theta_i " << o.theta_i_deg[a] << " channel " << c;
            EXPECT_EQ(e.transmitted[c], 0.0);
        }
        Slice sl = make_slice(r, a, kReflection);
        auto exact = [&](uint32_t t, uint32_t p, int c) {
            return bin_average(grid, t, p, [&](glm::dvec3 wo) {
                return exact_media::semi_infinite_isotropic_brdf(H[c], mu_i, wo.z, double(omega[c]));
            });
        };
        compare_bins(check, sl, grid, o.paths, 3, exact, "theta_i " + std::to_string(o.theta_i_deg[a]));
    }
    expect_matches(check, where(cpu) + " semi-infinite isotropic medium, every order");
}

// Single scattering in a thin layer of SGGX microflakes (fibres along the normal or flakes facing it), as
// single_scattering: an index-matched smooth top, a black base, the event cap at 3. The extinction along w is
// tau sigma(w), so f1 = omega D(h) (1 - exp(-tau (sigma_i / mu_i + sigma_o / mu_o))) / (4 (sigma_i mu_o + sigma_o mu_i))
// (the Henyey-Greenstein form with p = D(h) / (4 sigma_i) and each crossing's optical depth scaled by sigma), S and
// D from their closed forms here, not from medium.glsl.
void microflake_single_scattering(bool cpu, MediumPhase phase) {
    const glm::vec3 tau(0.2f, 0.5f, 1.0f), omega(0.9f, 0.6f, 0.3f);
    const double alpha = 0.5, sig = alpha * alpha;
    Layer fibres = scattering_layer(1.0f, tau, omega, 0.0f);
    fibres.phase = phase;
    fibres.fibre_roughness = float(alpha);
    Stack s = make_stack("single-microflake", {fibres, lambertian(glm::vec3(0.0f))});
    SimOptions o;
    o.theta_i_deg = {0.0, 40.5, 75.5};
    o.paths = cpu ? 2000000 : 6000000;
    o.dtheta_deg = 3;
    o.dphi_deg = 6;
    o.seed = 37;
    o.max_events = 3;
    SimResult r = run(s, o, cpu);
    BinGrid grid(r);
    BinCheck check;
    const bool fibre = phase == MediumPhase::SggxFibre;
    const glm::dvec3 S = fibre ? glm::dvec3(1, 1, sig * sig) : glm::dvec3(sig * sig, sig * sig, 1);
    auto area = [&](glm::dvec3 w) { return std::sqrt(glm::dot(w * w, S)); };
    auto ndf = [&](glm::dvec3 m) {
        const glm::dvec3 m2 = m * m / S;   // m^T S^-1 m, S diagonal
        const double q = m2.x + m2.y + m2.z;
        return 1.0 / (M_PI * std::sqrt(S.x * S.y * S.z) * q * q);
    };
    for (size_t a = 0; a < r.angles.size(); ++a) {
        const double ti = o.theta_i_deg[a] * M_PI / 180;
        const glm::dvec3 wi(std::sin(ti), 0, std::cos(ti));
        Slice sl = make_slice(r, a, kReflection);
        auto exact = [&](uint32_t t, uint32_t p, int c) {
            return bin_average(grid, t, p, [&](glm::dvec3 wo) {
                const double si = area(wi), so = area(wo);
                const double depth = double(tau[c]) * (si / wi.z + so / wo.z);
                return double(omega[c]) * ndf(glm::normalize(wi + wo)) * -std::expm1(-depth) /
                       (4 * (si * wo.z + so * wi.z));
            });
        };
        compare_bins(check, sl, grid, o.paths, 3, exact, "theta_i " + std::to_string(o.theta_i_deg[a]),
                     std::max({omega.x, omega.y, omega.z}));
    }
    expect_matches(check, where(cpu) + (fibre ? " SGGX fibres" : " SGGX flakes") + " single scattering");
}

// The sheen authors' published table (data/sheen/ltc-sheen-volume-reflectance.csv): R[mu_index][alpha_index]
std::vector<std::vector<double>> sheen_authors_table() {
    std::ifstream f(std::string(GONIO_SOURCE_DIR) + "/data/sheen/ltc-sheen-volume-reflectance.csv");
    std::vector<std::vector<double>> R(32, std::vector<double>(32, -1.0));
    std::string line;
    while (std::getline(f, line)) {
        if (line.empty() || line[0] == '#' || line[0] == 'm') continue;
        int i = 0, j = 0;
        double mu = 0, alpha = 0, r = 0;
        if (std::sscanf(line.c_str(), "%d,%d,%lf,%lf,%lf", &i, &j, &mu, &alpha, &r) == 5 && i >= 0 && i < 32 &&
            j >= 0 && j < 32)
            R[size_t(i)][size_t(j)] = r;
    }
    return R;
}

// The authors' slab: an index-matched top, a medium of fibres (optical depth 1, albedo 1), open at the bottom
Stack sheen_authors_slab(double alpha) {
    Layer fibres = scattering_layer(1.0f, glm::vec3(1.0f), glm::vec3(1.0f), 0.0f);
    fibres.phase = MediumPhase::SggxFibre;
    fibres.fibre_roughness = float(alpha);
    return make_stack("sheen-slab", {fibres, dielectric(1.0f)});
}

// The sheen authors' estimator exactly, on the CPU twin: their walk stops after 16 scattering events, and a path
// stopped there counts as reflected when its last direction points up (sheen_volume.h sample_impl, Brdf::sample;
// data/sheen/README.md). In gonio's walk that is max_events 17 (the entry, then at most 16 collisions; a path that
// leaves after its 15th has its exit as the 17th event) with the truncated paths that head up booked as reflected.
// Cells where the cap matters most (low alpha, grazing: the fibres keep the path's height, it scatters dozens of
// times; gonio's uncapped walk gives 0.279 at mu 0.01, alpha 0.032, theirs 0.058) and where it does not. Each
// cell's z = (gonio - theirs) / se (the two-proportion test, pooled p) within 4 (9 cells).
TEST(SheenAuthorsTable, TheirCappedEstimatorOnTheCpuTwin) {
    const auto R = sheen_authors_table();
    const double n_theirs = 2e6;
    const std::pair<int, int> cells[] = {{0, 1}, {0, 2}, {1, 2}, {1, 3}, {3, 4}, {0, 31}, {8, 8}, {16, 16}, {31, 31}};
    const uint64_t paths = 200000;
    for (auto [mi, ai] : cells) {
        const double mu = std::max(0.01, mi / 31.0), alpha = std::max(0.01, ai / 31.0);
        SimOptions o;
        o.theta_i_deg = {std::acos(mu) * 180 / M_PI};
        const WalkStack walk = walk_stack(sheen_authors_slab(alpha), true);
        CpuWalker walker(walk.gpu, walk.spec);
        const vec3 travel = incident_travel_of(o.theta_i_deg[0], 0.0);
        const uvec2 mix = rng_seed_mix(59u, uint32_t(mi * 32 + ai));
        uint64_t reflected = 0, stopped_up = 0;
        for (uint64_t i = 0; i < paths; ++i) {
            Rng rng = rng_init_mixed(uint32_t(i), 0u, mix);
            CpuWalker::Walk p;
            CpuWalker::PathResult r;
            walker.walk_begin(p, r, travel);
            for (uint it = 0u; it < 17u; ++it)
                if (!walker.walk_step(p, r, rng, 17u)) break;
            if (r.outcome == OUTCOME_REFLECTED) ++reflected;
            if (r.outcome == OUTCOME_TRUNCATED && p.alive && p.d.z > 0.0f) ++stopped_up;
        }
        const double ours = double(reflected + stopped_up) / double(paths), theirs = R[size_t(mi)][size_t(ai)];
        const double pooled = (ours * double(paths) + theirs * n_theirs) / (double(paths) + n_theirs);
        const double se = std::sqrt(pooled * (1 - pooled) * (1 / double(paths) + 1 / n_theirs));
        const double z = se > 0 ? (ours - theirs) / se : 0.0;
        std::printf(
            "their estimator: alpha %.4f mu %.4f: gonio %.5f (of it stopped heading up %.5f) authors %.5f z "
            "%+.2f\n",
            alpha, mu, ours, double(stopped_up) / double(paths), theirs, z);
        EXPECT_LT(std::fabs(z), 4.0) << "alpha " << alpha << " mu " << mu;
    }
}

class ScatteringWalk : public GpuTest {};

// gonio's walk against the sheen authors' published directional reflectance of their fibre slab (Zeltner, Burley &
// Chiang 2022; data/sheen/README.md), cell by cell: z = (gonio - theirs) / sqrt(se_gonio^2 + se_theirs^2), each a
// binomial proportion (every weight is 0 or 1 in a white slab), within 4 at every cell (15 cells: a false alarm 1e-3).
// Their walk stops at 16 scattering events and counts a path stopped while heading up as reflected; gonio's is not
// capped here (the difference is bounded by gonio's share of paths with more than 16 events, printed beside).
TEST_F(ScatteringWalk, SheenAuthorsTableOfTheFibreSlab) {
    const auto R = sheen_authors_table();
    const double n_theirs = 2e6;
    const int mus[] = {0, 3, 8, 16, 31}, alphas[] = {8, 16, 31};
    for (int ai : alphas) {
        const double alpha = std::max(0.01, ai / 31.0);
        SimOptions o;
        o.theta_i_deg.clear();
        for (int mi : mus) o.theta_i_deg.push_back(std::acos(std::max(0.01, mi / 31.0)) * 180 / M_PI);
        o.paths = 400000;
        o.seed = 53;
        o.max_events = 4000;
        SimResult r = simulate_gpu(context(), sheen_authors_slab(alpha), o);
        SimOptions capped = o;
        capped.max_events = 18;   // the entry, 16 scattering events, the exit
        capped.paths = 100000;
        SimResult rc = simulate_gpu(context(), sheen_authors_slab(alpha), capped);
        ASSERT_EQ(r.angles.size(), std::size(mus));
        for (size_t a = 0; a < r.angles.size(); ++a) {
            const int mi = mus[a];
            ASSERT_NEAR(r.angles[a].theta_i_deg, std::acos(std::max(0.01, mi / 31.0)) * 180 / M_PI, 1e-9);
            const double theirs = R[size_t(mi)][size_t(ai)];
            ASSERT_GE(theirs, 0.0) << "the table lacks a cell";
            const double ours = energy_book(r, a).reflected.y;
            const double se = std::sqrt(ours * (1 - ours) / double(o.paths) + theirs * (1 - theirs) / n_theirs);
            const double z = se > 0 ? (ours - theirs) / se : 0.0;
            std::printf("alpha %.4f mu %.4f: gonio %.5f authors %.5f z %+.2f; beyond 16 scattering events %.2g\n",
                        alpha, std::max(0.01, mi / 31.0), ours, theirs, z, energy_book(rc, a).truncated.y);
            EXPECT_LT(std::fabs(z), 4.0) << "alpha " << alpha << " mu index " << mi;
        }
    }
}

TEST_F(ScatteringWalk, MicroflakeSingleScatteringDevice) {
    microflake_single_scattering(false, MediumPhase::SggxFibre);
    microflake_single_scattering(false, MediumPhase::SggxFlake);
}
TEST_F(ScatteringWalk, MicroflakeSingleScatteringCpuTwin) {
    microflake_single_scattering(true, MediumPhase::SggxFibre);
}

// A white furnace of fibres: albedo 1 fibres (alpha 0.3, optical depth 3) over a white Lambertian base under an
// index-matched top: every path comes back. Grey, so every weight stays 1: reflected 1 to rounding.
TEST_F(ScatteringWalk, MicroflakeWhiteFurnace) {
    for (MediumPhase phase : {MediumPhase::SggxFibre, MediumPhase::SggxFlake}) {
        Layer fibres = scattering_layer(1.0f, glm::vec3(3.0f), glm::vec3(1.0f), 0.0f);
        fibres.phase = phase;
        fibres.fibre_roughness = 0.3f;
        Stack s = make_stack("fibre-furnace", {fibres, lambertian(glm::vec3(1.0f))});
        SimOptions o;
        o.theta_i_deg = {0.0, 60.0, 89.9};
        o.paths = 400000;
        o.max_events = 4000;
        o.seed = 47;
        SimResult r = simulate_gpu(context(), s, o);
        for (size_t a = 0; a < r.angles.size(); ++a) {
            const EnergyBook e = energy_book(r, a);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(e.reflected[c] + e.truncated[c], 1.0, 1e-5) << "theta_i " << o.theta_i_deg[a];
                EXPECT_LT(e.truncated[c], 1e-3);
                EXPECT_LT(std::fabs(e.absorbed[c]), 1e-5);
            }
            std::printf("microflake furnace phase %d theta_i %4.1f: reflected %.6f truncated %.2g\n", int(phase),
                        o.theta_i_deg[a], e.reflected.y, e.truncated.y);
        }
    }
}

TEST_F(ScatteringWalk, SingleScatteringDevice) { single_scattering(false, false); }
TEST_F(ScatteringWalk, SingleScatteringGeneralWalk) { single_scattering(false, true); }
TEST_F(ScatteringWalk, SingleScatteringCpuTwin) { single_scattering(true, false); }
TEST_F(ScatteringWalk, SemiInfiniteIsotropicDevice) { semi_infinite(false); }
TEST_F(ScatteringWalk, SemiInfiniteIsotropicCpuTwin) { semi_infinite(true); }

// White furnaces: no absorption anywhere, so all the light comes back. A conservative medium (optical depth 4, the
// same in every channel, so every weight stays exactly 1) under a smooth coat of index 1.5 (total internal
// reflection traps light in the medium) over a white base; and a milky slab in air, whose reflection and
// transmission sum to 1. Forward and backward phase functions.
TEST_F(ScatteringWalk, WhiteFurnaces) {
    for (float g : {0.8f, -0.5f}) {
        for (bool slab : {false, true}) {
            Stack s = slab ? make_stack("milky-slab",
                                        {scattering_layer(1.5f, glm::vec3(4.0f), glm::vec3(1.0f), g), dielectric(1.0f)})
                           : make_stack("furnace", {scattering_layer(1.5f, glm::vec3(4.0f), glm::vec3(1.0f), g),
                                                    lambertian(glm::vec3(1.0f))});
            SimOptions o;
            o.theta_i_deg = {0.0, 60.0, 89.9};
            o.paths = 400000;
            o.max_events = 4000;
            o.seed = 41;
            SimResult r = simulate_gpu(context(), s, o);
            for (size_t a = 0; a < r.angles.size(); ++a) {
                const EnergyBook e = energy_book(r, a);
                for (int c = 0; c < 3; ++c) {
                    const std::string what = s.name + " g " + std::to_string(g) + " theta_i " +
                                             std::to_string(o.theta_i_deg[a]) + " channel " + std::to_string(c);
                    EXPECT_NEAR(e.reflected[c] + e.transmitted[c] + e.truncated[c], 1.0, 1e-5) << what;
                    EXPECT_LT(e.truncated[c], 1e-3) << what;
                    EXPECT_LT(std::fabs(e.absorbed[c]), 1e-5) << what;
                    EXPECT_EQ(e.microfacet_loss[c], 0.0) << what;
                    if (!slab) { EXPECT_EQ(e.transmitted[c], 0.0) << what; }
                }
                // the slab transmits (but at grazing incidence, where the top's Fresnel reflection is 0.996)
                if (slab && o.theta_i_deg[a] < 80) { EXPECT_GT(e.transmitted.y, 0.2) << "the slab transmits"; }
                std::printf("%s g %+.1f theta_i %4.1f: reflected %.6f transmitted %.6f truncated %.2g\n",
                            s.name.c_str(), g, o.theta_i_deg[a], e.reflected.y, e.transmitted.y, e.truncated.y);
            }
        }
    }
}

// A furnace whose optical depth differs per channel: the free flight's weights then differ from 1 per channel (the
// balance over channels), and Russian roulette books their fluctuations as absorbed, zero on average. What comes
// back is 1 per channel to a few standard errors (the weights' spread is below 1, so se < 1 / sqrt(paths)).
TEST_F(ScatteringWalk, WhiteFurnaceWithRgbOpticalDepth) {
    Stack s = make_stack("furnace-rgb", {scattering_layer(1.5f, glm::vec3(0.5f, 2.0f, 8.0f), glm::vec3(1.0f), 0.5f),
                                         lambertian(glm::vec3(1.0f))});
    SimOptions o;
    o.theta_i_deg = {0.0, 70.0};
    o.paths = 1000000;
    o.max_events = 4000;
    o.seed = 43;
    SimResult r = simulate_gpu(context(), s, o);
    for (size_t a = 0; a < r.angles.size(); ++a) {
        const EnergyBook e = energy_book(r, a);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(e.reflected[c], 1.0, 5.0 / std::sqrt(double(o.paths)))
                << "theta_i " << o.theta_i_deg[a] << " channel " << c;
            EXPECT_LT(e.truncated[c], 1e-4);
        }
    }
}

// A path that scatters back up in the medium without reaching the base reverses its direction once beneath the top
// surface: path class 1, as a trip to the base and back. Single scattering (the setting of single_scattering) is
// therefore all class 1; with an index-matched top nothing is class 0.
TEST_F(ScatteringWalk, ScatteredBackIsClassOne) {
    Stack s = make_stack("single",
                         {scattering_layer(1.0f, glm::vec3(0.5f), glm::vec3(0.9f), 0.0f), lambertian(glm::vec3(0.0f))});
    SimOptions o;
    o.theta_i_deg = {40.0};
    o.paths = 500000;
    o.max_events = 3;
    o.orders = true;
    SimResult r = simulate_gpu(context(), s, o);
    double total = 0, class1 = 0, other = 0;
    for (const auto& v : make_slice(r, 0, kReflection, -1).sum) total += v.y;
    for (const auto& v : make_slice(r, 0, kReflection, 1).sum) class1 += v.y;
    for (int cls : {0, 2})
        for (const auto& v : make_slice(r, 0, kReflection, cls).sum) other += v.y;
    EXPECT_GT(total, 0.05);
    EXPECT_DOUBLE_EQ(class1, total);
    EXPECT_EQ(other, 0.0);
}

}   // namespace
