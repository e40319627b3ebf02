// Hard cases (stacks/hard/*.toml) and seeded random stacks (host/core/random_stack.h) through the reference and every
// model that can represent them: finite everywhere, energy booked and bounded, reciprocal where a model claims
// it, and standard errors that match the spread of independent runs.
#include "model_twin_on_stack.h"
#include "gpu_fixture.h"
#include "stack_gpu.h"
#include "models.h"
#include "model_quadrature.h"
#include "random_stack.h"
#include "stack_vocabulary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>

using namespace gonio;
using namespace gonio_test;

namespace {

constexpr uint64_t kRandomSeed = 4;   // the generated batch: gonio random-stack --seed 4 --count 12
constexpr int kRandomCount = 12;

std::vector<Stack> hard_stacks() {
    std::vector<std::string> files;
    for (auto& e : std::filesystem::directory_iterator("stacks/hard"))
        if (e.path().extension() == ".toml") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    std::vector<Stack> out;
    for (auto& f : files) out.push_back(parse_stack_file(f));
    return out;
}

std::vector<Stack> all_stacks() {
    std::vector<Stack> s = hard_stacks();
    for (int i = 0; i < kRandomCount; ++i) s.push_back(random_stack(kRandomSeed, uint64_t(i)));
    return s;
}

class HardCases : public GpuTest {};

// ---- the generator ----------------------------------------------------------------------------------------

// The suite must hold what the issue asks for: roughness 0, 1e-4 and 1; IOR ratio 1; IOR 3; optical depth 0
// and 50; k = 10; at least 8 layers; a total-internal-reflection trap (relative IOR >= 2 under a smooth face).
TEST(HardCaseSuite, CoversTheRequiredCases) {
    std::vector<Stack> hs = hard_stacks();
    ASSERT_GE(hs.size(), 12u);
    bool r0 = false, r4 = false, r1 = false, matched = false, ior3 = false, tau0 = false, tau50 = false, k10 = false,
         many = false, tir = false;
    for (auto& s : hs) {
        many |= s.layers.size() >= 8;
        for (size_t i = 0; i < s.layers.size(); ++i) {
            const Layer& L = s.layers[i];
            if (L.kind == InterfaceKind::Lambertian) continue;
            r0 |= L.roughness == 0.0f;
            r4 |= L.roughness == 1e-4f;
            r1 |= L.roughness == 1.0f;
            k10 |= L.kind == InterfaceKind::Conductor && L.k.x >= 10.0f;
            if (L.kind != InterfaceKind::Dielectric) continue;
            float above = s.ior_above(i).x;
            matched |= L.ior.x == above;
            ior3 |= L.ior.x >= 3.0f;
            tir |= L.ior.x / above >= 2.0f && L.roughness == 0.0f;
            if (i + 1 < s.layers.size()) {
                tau0 |= L.optical_depth == glm::vec3(0.0f);
                tau50 |= std::max(L.optical_depth.x, std::max(L.optical_depth.y, L.optical_depth.z)) >= 50.0f;
            }
        }
    }
    EXPECT_TRUE(r0 && r4 && r1) << "roughness 0, 1e-4 and 1";
    EXPECT_TRUE(matched) << "an index-matched interface";
    EXPECT_TRUE(ior3) << "IOR 3";
    EXPECT_TRUE(tau0 && tau50) << "optical depth 0 and 50";
    EXPECT_TRUE(k10) << "conductor k = 10";
    EXPECT_TRUE(many) << "at least 8 layers";
    EXPECT_TRUE(tir) << "a total-internal-reflection trap";
}

// Same seed, same stacks; every stack valid and read back from its own TOML exactly; over many seeds the
// generator reaches every corner it promises (random_stack.h).
TEST(RandomStacks, DeterministicValidAndCoveringTheSpace) {
    for (int i = 0; i < 5; ++i) EXPECT_EQ(random_stack_toml(7, uint64_t(i)), random_stack_toml(7, uint64_t(i)));
    EXPECT_NE(random_stack_toml(7, 0), random_stack_toml(8, 0));
    EXPECT_NE(random_stack_toml(7, 0), random_stack_toml(7, 1));
    int kinds[3] = {}, r0 = 0, r4 = 0, r1 = 0, matched = 0, ior3 = 0, tau0 = 0, tau50 = 0, k10 = 0, many = 0, one = 0,
        exterior = 0;
    for (int i = 0; i < 400; ++i) {
        std::string text = random_stack_toml(11, uint64_t(i));
        Stack s = parse_stack_string(text, "generated.toml");   // throws if the generator wrote an invalid stack
        EXPECT_EQ(stack_to_toml(s), text) << "stack " << i << " does not read back to itself";
        EXPECT_EQ(s.name, "random-11-" + std::to_string(i));
        kinds[int(s.base().kind)]++;
        many += s.layers.size() >= 8;
        one += s.layers.size() == 1;
        exterior += s.exterior_ior != 1.0f;
        for (size_t l = 0; l < s.layers.size(); ++l) {
            const Layer& L = s.layers[l];
            if (L.kind == InterfaceKind::Lambertian) continue;
            r0 += L.roughness == 0.0f;
            r4 += L.roughness == 1e-4f;
            r1 += L.roughness == 1.0f;
            k10 += L.kind == InterfaceKind::Conductor && L.k == glm::vec3(10.0f);
            if (L.kind == InterfaceKind::Dielectric) {
                matched += L.ior.x == s.ior_above(l).x;
                ior3 += L.ior.x == 3.0f;
                if (l + 1 < s.layers.size()) {
                    tau0 += L.optical_depth == glm::vec3(0.0f);
                    tau50 += L.optical_depth == glm::vec3(50.0f);
                }
            }
        }
    }
    for (int k = 0; k < 3; ++k) EXPECT_GT(kinds[k], 60) << "base kind " << k;
    // every key of every kind (stack_vocabulary.h) is drawn away from its default somewhere: a key added to the
    // vocabulary without a draw here fails
    for (const LayerKey& key : layer_keys()) {
        int drawn = 0;
        for (int i = 0; i < 400; ++i) {
            const Stack s = random_stack(11, uint64_t(i));
            for (const Layer& L : s.layers) drawn += L.kind == key.kind && key.get(L) != glm::vec3(key.fallback);
        }
        EXPECT_GE(drawn, 10) << to_string(key.kind) << " " << key.name;
    }
    // and every word key (the microsurface's) away from its default, on both kinds it is a key of
    for (const ChoiceKey& c : choice_keys())
        for (InterfaceKind kind : c.kinds) {
            int drawn = 0;
            for (int i = 0; i < 400; ++i)
                for (const Layer& L : random_stack(11, uint64_t(i)).layers) drawn += L.kind == kind && c.get(L) != 0;
            EXPECT_GE(drawn, 10) << to_string(kind) << " " << c.name;
        }
    for (int n : {r0, r4, r1, matched, ior3, tau0, tau50, k10, many, one, exterior}) EXPECT_GE(n, 10);
    // options: a two-layer coat over a conductor only (the atlas's family)
    RandomStackOptions o;
    o.min_layers = o.max_layers = 2;
    o.lambertian_base = o.transmissive = false;
    for (int i = 0; i < 50; ++i) {
        Stack s = random_stack(3, uint64_t(i), o);
        ASSERT_EQ(s.layers.size(), 2u);
        EXPECT_EQ(s.base().kind, InterfaceKind::Conductor);
    }
    o.conductor_base = false;
    EXPECT_THROW(random_stack(3, 0, o), std::invalid_argument);
}

// ---- the reference ----------------------------------------------------------------------------------------

// Finite everywhere, every energy fraction in [0, 1] (absorbed may dip below 0 by the Russian-roulette balance,
// which is zero on average), reflected + transmitted + absorbed + lost + truncated = 1 within rounding.
//
// The rounding, per path: the exit weight and its square are quantised by unbiased stochastic rounding to
// 2^-12 (error sd <= 2^-13 per path, so <= 2^-13 / sqrt(N) for the mean: 4e-7 at N = 1e5), the book entries
// by rounding to nearest 2^-24 (<= 1.5 2^-24 = 9e-8 per path), and float32 arithmetic in the walk (a few
// roundings of 2^-24 relative per event). 2e-5 bounds all of it for every stack here, with room for the
// events of trapped paths (measured: at most 5.5e-7).
void expect_energy_booked(const SimResult& r, const std::string& what) {
    for (size_t a = 0; a < r.angles.size(); ++a) {
        EnergyBook e = energy_book(r, a);
        for (int c = 0; c < 3; ++c) {
            std::string where =
                what + " theta_i " + std::to_string(r.angles[a].theta_i_deg) + " channel " + std::to_string(c);
            EXPECT_NEAR(e.sum()[c], 1.0, 2e-5) << where;
            for (double v : {e.reflected[c], e.transmitted[c], e.absorbed[c], e.microfacet_loss[c], e.truncated[c]})
                ASSERT_TRUE(std::isfinite(v)) << where;
            for (double v : {e.reflected[c], e.transmitted[c], e.microfacet_loss[c], e.truncated[c]}) {
                EXPECT_GE(v, 0.0) << where;
                EXPECT_LE(v, 1.0 + 1e-12) << where;
            }
            // the full walk: each exit weight is at most 1 and is quantised to at most 1, so R + T <= 1 but for the
            // rounding of the double-precision sums over bins. The Lambertian series' exits weigh up to S: R + T <= 1
            // within its noise (4.5 standard errors), and absorbed, the rest, >= 0 within the same noise; so do the
            // booking estimators' (a path books its own exit, the entry's reflected branch and its exit estimates:
            // the se's bound, exit_fraction_se_bound)
            const int bookings = 1 + int(r.walk.entry_branch) + int(r.walk.exit_estimates);
            const bool series = r.walk.series, estimators = bookings > 1;
            const double noise = series       ? 4.5 * exit_fraction_se(r, a, c)
                                 : estimators ? 4.5 * exit_fraction_se_bound(r, a, c, bookings)
                                              : 0.0;
            EXPECT_GE(e.absorbed[c], -1e-3 - noise) << where;
            EXPECT_LE(e.reflected[c] + e.transmitted[c], 1.0 + 1e-12 + noise) << where;
        }
    }
}

void expect_bins_finite(const SimResult& r, const std::string& what) {
    for (size_t a = 0; a < r.angles.size(); ++a)
        for (int side = 0; side < 2; ++side) {
            Slice s = make_slice(r, a, Side(side));
            for (size_t b = 0; b < s.f.size(); ++b)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(s.f[b][c]) && s.f[b][c] >= 0)
                        << what << " bin " << b << " f " << s.f[b][c];
                    ASSERT_TRUE(std::isfinite(s.se[b][c]) && s.se[b][c] >= 0)
                        << what << " bin " << b << " se " << s.se[b][c];
                }
        }
}

TEST_F(HardCases, ReferenceIsFiniteAndBooksAllEnergy) {
    SimOptions o;
    o.theta_i_deg = {0, 60, 89.9};
    o.paths = 200000;
    double worst = 0;
    for (auto& s : all_stacks()) {
        SimResult r = simulate_gpu(context(), s, o);
        expect_bins_finite(r, s.name);
        expect_energy_booked(r, s.name);
        for (size_t a = 0; a < r.angles.size(); ++a)
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(energy_book(r, a).sum()[c] - 1.0));
        if (s.name == "transparent") {   // index-matched everywhere: all of it straight through
            for (size_t a = 0; a < r.angles.size(); ++a) EXPECT_NEAR(energy_book(r, a).transmitted.x, 1.0, 1e-6);
        }
        if (walk_spec(s, true).series) {   // where the series ran: the walk that traces every trip, held exactly
            SimOptions full = o;
            full.series = false;
            SimResult f = simulate_gpu(context(), s, full);
            expect_bins_finite(f, s.name + " (--no-series)");
            expect_energy_booked(f, s.name + " (--no-series)");
        }
    }
    std::printf("largest |R + T + absorbed + lost + truncated - 1|: %.3g\n", worst);
    // the general N-layer walk on the deepest stacks
    o.specialised = false;
    for (auto& s : hard_stacks())
        if (s.layers.size() >= 8) {
            SimResult r = simulate_gpu(context(), s, o);
            expect_bins_finite(r, s.name + " (general walk)");
            expect_energy_booked(r, s.name + " (general walk)");
        }
}

// Standard errors are honest on every case: K independent replicates (the same incident angle repeated: each
// angle index has its own random stream) of N paths; per bin-channel j the between-replicate variance v_j
// against the mean reported se^2 (s2_j). R = sum v_j / sum s2_j must be 1 within its sampling error:
//  - v_j is a sample variance of K values whose covariance matrix C has C_jj = sigma_j^2 (the reported se^2
//    estimates it), between channels of one bin |C| <= sigma_c sigma_d (Cauchy-Schwarz: the runs keep no cross
//    moments), and between different bins C_ij = -f_i f_j / N exactly (a path leaves through one bin only).
//    For near-Gaussian bin values (every counted bin holds >= 100 paths' weight; 10 x 20 degree bins, so that
//    diffuse lobes qualify), Var(sum v) = 2/(K-1) ||C||_F^2,
//    so sum v / sum sigma^2 ~ chi2_nu / nu with nu = (K-1) (sum sigma^2)^2 / ||C||_F^2 (Satterthwaite).
//  - The bounds are that distribution's quantiles at z = 4.5 (Wilson-Hilferty), widened by 4.5 times the
//    relative standard deviation of sum s2 (from the spread of each replicate's sum of se^2). Over the ~30
//    cases the chance of a false alarm is below 1e-3, and the seeds are fixed, so the test is reproducible.
//  - Pooled over the cases (independent runs): the mean of the ratios has variance sum (2 / nu + the
//    denominator's relative variance) / n^2, and must be 1 within 4.5 of its standard deviations: a sharp test
//    (a few percent) where each case alone, with few bins, is a loose one.
TEST_F(HardCases, StandardErrorsAreHonest) {
    const int K = 16;
    SimOptions o;
    o.paths = 100000;
    o.dtheta_deg = 10;
    o.dphi_deg = 20;
    o.seed = 77;
    const double angles[3] = {0, 60, 89.9};
    int index = 0, tested = 0;
    double pooled = 0, pooled_var = 0;
    for (auto& s : all_stacks()) {
        double ti = angles[index++ % 3];
        o.theta_i_deg.assign(K, ti);
        SimResult r = simulate_gpu(context(), s, o);
        expect_energy_booked(r, s.name + " (replicates)");
        BinGrid g(r);
        std::vector<std::vector<Slice>> runs(2);
        for (int side = 0; side < 2; ++side)
            for (int k = 0; k < K; ++k) runs[side].push_back(make_slice(r, size_t(k), Side(side)));
        double sum_v = 0, sum_s2 = 0, frob = 0, sum_f2 = 0, same_bin_f4 = 0;
        std::vector<double> per_run(K, 0.0);
        int counted = 0;
        for (int side = 0; side < 2; ++side)
            for (size_t b = 0; b < runs[side][0].f.size(); ++b) {
                double s2_bin = 0, f2_bin = 0;
                for (int c = 0; c < 3; ++c) {
                    double mean = 0, s2 = 0;
                    for (auto& x : runs[side]) {
                        mean += x.f[b][c] / K;
                        s2 += x.se[b][c] * x.se[b][c] / K;
                    }
                    double omega = g.projected_solid_angle(uint32_t(b / g.n_phi));
                    if (mean * omega * double(o.paths) < 100 || !(s2 > 0)) continue;
                    double v = 0;
                    for (auto& x : runs[side]) v += (x.f[b][c] - mean) * (x.f[b][c] - mean) / (K - 1);
                    for (int k = 0; k < K; ++k) per_run[k] += runs[side][k].se[b][c] * runs[side][k].se[b][c];
                    sum_v += v;
                    sum_s2 += s2;
                    s2_bin += s2;
                    f2_bin += mean * mean;
                    counted++;
                }
                frob += s2_bin * s2_bin;
                sum_f2 += f2_bin;
                same_bin_f4 += f2_bin * f2_bin;
            }
        if (counted == 0) {
            std::printf(
                "%-26s theta_i %4g: no bin with spread (every path leaves with the same weight in the same bin)\n",
                s.name.c_str(), ti);
            continue;
        }
        frob += (sum_f2 * sum_f2 - same_bin_f4) / (double(o.paths) * double(o.paths));
        const double nu = (K - 1) * sum_s2 * sum_s2 / frob;
        double m = 0, var_t = 0;
        for (double t : per_run) m += t / K;
        for (double t : per_run) var_t += (t - m) * (t - m) / (K - 1);
        const double rel_sd_den = std::sqrt(var_t / K) / sum_s2;
        const double z = 4.5, h = 2.0 / (9.0 * nu);
        const double lo = std::pow(std::max(0.0, 1 - h - z * std::sqrt(h)), 3) - z * rel_sd_den;
        const double hi = std::pow(1 - h + z * std::sqrt(h), 3) + z * rel_sd_den;
        const double ratio = sum_v / sum_s2;
        std::printf("%-26s theta_i %4g: %4d bin-channels, nu %7.1f, variance / se^2 = %.3f, allowed [%.3f, %.3f]\n",
                    s.name.c_str(), ti, counted, nu, ratio, lo, hi);
        EXPECT_GT(ratio, lo) << s.name;
        EXPECT_LT(ratio, hi) << s.name;
        pooled += ratio;
        pooled_var += 2.0 / nu + rel_sd_den * rel_sd_den;
        tested++;
    }
    ASSERT_GE(tested, 25);
    pooled /= tested;
    const double sd = std::sqrt(pooled_var) / tested;
    std::printf("pooled over %d cases: mean variance / se^2 = %.4f, allowed 1 +- %.4f\n", tested, pooled, 4.5 * sd);
    EXPECT_NEAR(pooled, 1.0, 4.5 * sd);
}

// ---- the models -------------------------------------------------------------------------------------------

double omega(const ModelGrid& g, uint32_t t) {
    double lo = t * g.dtheta_deg * M_PI / 180, hi = (t + 1) * g.dtheta_deg * M_PI / 180;
    return 0.5 * (std::pow(std::sin(hi), 2) - std::pow(std::sin(lo), 2)) * g.dphi_deg * M_PI / 180;
}

// The sheen models' one shape at its edges (no hard stack or random stack has it: a fibre layer of optical depth
// exactly 1 under an index-matched top): white fibres at the range's thinnest alpha and at alpha 1 over white, and
// black fibres (albedo 0) over black; models only, the fibres' reference is tests/test_scattering_walk.cpp's
namespace {
std::vector<Stack> fibre_cases() {
    std::vector<Stack> out;
    for (const auto& [name, alpha, fibres, base] : {std::tuple{"fibres-alpha-0.01-over-white", "0.01", "1.0", "1.0"},
                                                    std::tuple{"fibres-alpha-1-over-white", "1.0", "1.0", "1.0"},
                                                    std::tuple{"black-fibres-over-black", "0.3", "0.0", "0.0"}})
        out.push_back(parse_stack_string(
            std::string("name = \"") + name +
                "\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nior = 1.0\noptical_depth = 1.0\n"
                "scattering_albedo = " +
                fibres + "\nphase = \"sggx-fibre\"\nfibre_roughness = " + alpha +
                "\n[[layer]]\ninterface = \"lambertian\"\nalbedo = " + base + "\n",
            std::string(name) + ".toml"));
    return out;
}
}   // namespace

// Every applicable model on every case, on the device (bin averages): finite and non-negative in every bin,
// both sides, at 0, 60 and 89.9 degrees; directional albedo (reflected + transmitted) <= 1 + 1e-3 for the models
// whose construction conserves energy (1e-3: the bin integration's error bound, tests/test_models.cpp and
// ModelBinsAtGrazing below), at every angle. The others' excess is printed (documented in docs/MODELS.md).
TEST_F(HardCases, ModelsAreFiniteAndBounded) {
    ModelEvaluator ev(context());
    ModelGrid g{45, 90, 2.0, 4.0, {0, 60, 89.9}};
    const auto& reg = model_registry();
    std::vector<double> largest(reg.size(), 0.0);
    std::vector<std::string> where(reg.size());
    std::vector<int> applied(reg.size(), 0);
    std::vector<Stack> stacks = all_stacks();
    for (Stack& s : fibre_cases()) stacks.push_back(std::move(s));
    for (auto& s : stacks) {
        auto all = ev.evaluate(s, g);
        ASSERT_EQ(all.size(), reg.size());
        for (size_t m = 0; m < all.size(); ++m) {
            const ModelSlices& ms = all[m];
            EXPECT_EQ(ms.not_applicable.empty(), model_cannot_represent(m, s).empty());
            if (!ms.not_applicable.empty()) continue;
            applied[m]++;
            ASSERT_EQ(ms.f.size(), g.theta_i_deg.size()) << ms.id;
            for (size_t a = 0; a < g.theta_i_deg.size(); ++a) {
                glm::dvec3 albedo(0);
                for (int side = 0; side < 2; ++side) {
                    if (side == 1 && ms.t.empty()) continue;
                    const auto& f = side == 0 ? ms.f[a] : ms.t[a];
                    ASSERT_EQ(f.size(), size_t(g.n_theta) * g.n_phi);
                    for (size_t b = 0; b < f.size(); ++b) {
                        for (int c = 0; c < 3; ++c)
                            ASSERT_TRUE(std::isfinite(f[b][c]) && f[b][c] >= 0)
                                << s.name << " " << ms.id << " theta_i " << g.theta_i_deg[a] << (side ? " T" : " R")
                                << " bin " << b << ": " << f[b][c];
                        albedo += f[b] * omega(g, uint32_t(b / g.n_phi));
                    }
                }
                for (int c = 0; c < 3; ++c) {
                    if (albedo[c] > largest[m]) {
                        largest[m] = albedo[c];
                        where[m] = s.name + " at theta_i " + std::to_string(g.theta_i_deg[a]);
                    }
                    if (reg[m].energy_conserving) {
                        EXPECT_LE(albedo[c], 1.0 + 1e-3) << ms.id << " claims energy conservation; " << s.name
                                                         << " theta_i " << g.theta_i_deg[a] << " channel " << c;
                    }
                }
            }
        }
    }
    // a +tir variant is not computed where no medium absorbs, as it equals its base model there (test_models:
    // TirVariantEqualsItsBaseWhereNothingAbsorbs): the base's excess on those cases is the variant's
    std::vector<double> as_base(largest);
    std::vector<std::string> where_base(where);
    for (size_t m = 0; m < reg.size(); ++m) {
        const std::string& id = reg[m].id;
        if (id.size() < 4 || id.substr(id.size() - 4) != "+tir") continue;
        for (size_t b = 0; b < reg.size(); ++b)
            if (reg[b].id == id.substr(0, id.size() - 4) && largest[b] > as_base[m]) {
                as_base[m] = largest[b];
                where_base[m] = where[b] + " (as " + reg[b].id + ", where nothing absorbs)";
            }
    }
    largest = as_base;
    where = where_base;
    for (size_t m = 0; m < reg.size(); ++m) {
        std::printf("%-20s on %2d cases; largest directional albedo %.4f (%s)%s\n", reg[m].id.c_str(), applied[m],
                    largest[m], where[m].c_str(),
                    reg[m].energy_conserving ? "" : " [not energy-conserving by construction]");
        // enterprise-pbr takes clear coats of IOR 1.5 over a Lambertian only, of which the hard cases hold one
        // (roughness-1-lambertian); its smooth coat and grazing light are in Models.EnterprisePbrIsTheSpecificationsFormula
        // and the renders' furnaces (tests/test_render.cpp)
        EXPECT_GE(applied[m], reg[m].id == "enterprise-pbr" ? 1 : 3)
            << reg[m].id << ": the hard cases should exercise every model";
        // a model documented as not energy-conserving must measurably exceed 1 somewhere (the claim is measured,
        // not assumed); tm21 (and tm21+g2) and belcour18-toplobe with the separable tables (the default and +tir) are
        // not bounded by construction, but no case here exceeds 1 (their registry notes say so); nor enterprise-pbr,
        // whose bound over a white base is measured in Models.EnterprisePbrIsTheSpecificationsFormula, nor
        // openpbr-adobe+reciprocal (its note)
        const std::string& id = reg[m].id;
        const bool no_excess_found = id.substr(0, id.find('+')) == "tm21" || id == "belcour18-toplobe" ||
                                     id == "belcour18-toplobe+tir" || id == "enterprise-pbr" ||
                                     id == "openpbr-adobe+reciprocal";
        if (!reg[m].energy_conserving && !no_excess_found) {
            EXPECT_GT(largest[m], 1.0 + 1e-3)
                << reg[m].id << " is documented as not energy-conserving, but measured bounded";
        }
    }
}

// Every model at single pairs of directions through the CPU twin (model_value_cpu), where the numerics are
// hardest: light and view at 89.9 degrees, exactly at the normal, at the mirror direction of a roughness 0 or
// 1e-4 lobe, and azimuths 0, 90 and 180; the transmission side for models with a transmitted lobe. Finite and
// non-negative; f(l, v) = f(v, l) (relative 1e-4 beyond 1e-6 of the larger value's scale) for the models the
// registry calls reciprocal.
TEST(HardCasesCpu, ModelValuesAreFiniteAndReciprocalAsClaimed) {
    const auto& reg = model_registry();
    const double thetas[] = {0.0, 1e-3, 30.0, 60.0, 85.0, 89.9};
    const double phis[] = {0.0, 90.0, 180.0};
    auto dir = [](double th, double ph) {
        double t = th * M_PI / 180, p = ph * M_PI / 180;
        return glm::vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t)));
    };
    std::vector<double> worst_asym(reg.size(), 0.0);
    std::vector<int> evaluated(reg.size(), 0);
    for (auto& s : all_stacks()) {
        for (size_t m = 0; m < reg.size(); ++m) {
            if (!model_cannot_represent(m, s).empty()) continue;
            const bool t_side = s.transmissive();
            for (double ti : thetas) {
                glm::vec3 l = dir(ti, 0.0);
                std::vector<glm::vec3> views;
                views.push_back(glm::vec3(-l.x, -l.y, l.z));   // the mirror direction
                for (double tv : thetas)
                    for (double pv : phis) views.push_back(dir(tv, pv));
                for (glm::vec3 v : views) {
                    glm::dvec3 f = model_value_cpu(m, s, l, v);
                    evaluated[m]++;
                    for (int c = 0; c < 3; ++c)
                        ASSERT_TRUE(std::isfinite(f[c]) && f[c] >= 0)
                            << s.name << " " << reg[m].id << " l (" << l.x << ", " << l.z << ") v (" << v.x << ", "
                            << v.y << ", " << v.z << "): " << f[c];
                    if (t_side) {
                        glm::dvec3 ft = model_value_cpu(m, s, l, glm::vec3(v.x, v.y, -v.z));
                        for (int c = 0; c < 3; ++c)
                            ASSERT_TRUE(std::isfinite(ft[c]) && ft[c] >= 0)
                                << s.name << " " << reg[m].id << " transmission side, l (" << l.x << ", " << l.z
                                << ") v (" << v.x << ", " << v.y << ", " << -v.z << "): " << ft[c];
                    }
                    if (!reg[m].reciprocal) continue;
                    glm::dvec3 b = model_value_cpu(m, s, v, l);
                    for (int c = 0; c < 3; ++c) {
                        double scale = std::max(std::fabs(f[c]), std::fabs(b[c]));
                        double d = std::fabs(f[c] - b[c]);
                        if (scale > 1e-6) worst_asym[m] = std::max(worst_asym[m], d / scale);
                        EXPECT_LE(d, 1e-4 * scale + 1e-6)
                            << reg[m].id << " claims reciprocity; " << s.name << " l (" << l.x << ", " << l.y << ", "
                            << l.z << ") v (" << v.x << ", " << v.y << ", " << v.z << "): " << f[c] << " vs " << b[c];
                    }
                }
            }
        }
    }
    for (size_t m = 0; m < reg.size(); ++m)
        std::printf("%-20s %6d evaluations; %s\n", reg[m].id.c_str(), evaluated[m],
                    reg[m].reciprocal ? ("largest relative asymmetry " + std::to_string(worst_asym[m])).c_str()
                                      : "not reciprocal by its registry entry");
}

// Directional albedo of a model, reflected + transmitted, by quadrature (model_quadrature.h).
glm::dvec3 albedo_by_quadrature(size_t model, const Stack& s, double theta_i_deg, double a, bool t_side) {
    return gonio::albedo_by_quadrature(model, s, theta_i_deg, a, t_side, 600, 360);
}

double narrowest_roughness(const Stack& s) {
    double a = 1.0;
    for (auto& L : s.layers)
        if (L.kind != InterfaceKind::Lambertian) a = std::min(a, double(std::max(L.roughness, 1e-4f)));
    return a;
}

// The energy claim at grazing incidence (89.9 degrees), through the CPU twin and an independent quadrature:
// models whose construction conserves energy reflect and transmit at most 1 + 1e-3 (the quadrature's own error
// is below 1e-4 on smooth lobes; tests/test_models.cpp).
TEST(HardCasesCpu, ModelAlbedoAtGrazing) {
    const auto& reg = model_registry();
    for (auto& s : all_stacks())
        for (size_t m = 0; m < reg.size(); ++m) {
            if (!reg[m].energy_conserving || !model_cannot_represent(m, s).empty()) continue;
            glm::dvec3 e = albedo_by_quadrature(m, s, 89.9, narrowest_roughness(s), s.transmissive());
            std::printf("%-26s %-18s albedo at 89.9 degrees (quadrature) %.4f %.4f %.4f\n", s.name.c_str(),
                        reg[m].id.c_str(), e.x, e.y, e.z);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(e[c])) << s.name << " " << reg[m].id;
                EXPECT_LE(e[c], 1.0 + 1e-3)
                    << reg[m].id << " claims energy conservation; " << s.name << " channel " << c;
            }
        }
}

// The models' bin averages at grazing incidence (89 and 89.9 degrees, 1 x 2 degree bins) sum to the directional
// albedo of the independent quadrature above within 1e-3, reflected + transmitted, on every hard case (as
// tests/test_models.cpp proves at 0 to 80 degrees on the shipped stacks), and are finite. This is where a lobe is
// squeezed against the horizon into an azimuthal sliver 2 alpha cos(theta_i) wide (host/models/model_plan.cpp
// plan()), where a base lobe at refracted directions is stretched 60x in theta, and where Belcour's symmetric lobes
// change fastest in mu.
TEST_F(HardCases, ModelBinsAtGrazing) {
    ModelGrid g{90, 180, 1.0, 2.0, {89.0, 89.9}};
    ModelEvaluator ev(context());
    double worst = 0.0;
    std::string where;
    for (auto& s : hard_stacks()) {
        auto all = ev.evaluate(s, g);
        for (size_t m = 0; m < all.size(); ++m) {
            if (!all[m].not_applicable.empty()) continue;
            for (size_t a = 0; a < g.theta_i_deg.size(); ++a) {
                glm::dvec3 sum(0);
                for (size_t b = 0; b < all[m].f[a].size(); ++b) {
                    for (int c = 0; c < 3; ++c)
                        ASSERT_TRUE(std::isfinite(all[m].f[a][b][c])) << s.name << " " << all[m].id << " bin " << b;
                    sum += all[m].f[a][b] * omega(g, uint32_t(b / g.n_phi));
                    if (!all[m].t.empty()) {
                        for (int c = 0; c < 3; ++c)
                            ASSERT_TRUE(std::isfinite(all[m].t[a][b][c]))
                                << s.name << " " << all[m].id << " T bin " << b;
                        sum += all[m].t[a][b] * omega(g, uint32_t(b / g.n_phi));
                    }
                }
                glm::dvec3 q = albedo_by_quadrature(m, s, g.theta_i_deg[a], narrowest_roughness(s), !all[m].t.empty());
                for (int c = 0; c < 3; ++c) {
                    if (std::fabs(sum[c] - q[c]) > worst) {
                        worst = std::fabs(sum[c] - q[c]);
                        where = s.name + " " + all[m].id + " at " + std::to_string(g.theta_i_deg[a]);
                    }
                    if (s.name == "dense-exterior" && c == 0)
                        std::printf("%-16s %-20s %5.1f deg: bins %.4f, quadrature %.4f\n", s.name.c_str(),
                                    all[m].id.c_str(), g.theta_i_deg[a], sum[c], q[c]);
                    EXPECT_NEAR(sum[c], q[c], 1e-3)
                        << s.name << " " << all[m].id << " theta_i " << g.theta_i_deg[a] << " channel " << c;
                }
            }
        }
    }
    std::printf("bins against quadrature at grazing: largest difference %.2e (%s)\n", worst, where.c_str());
}

}   // namespace
