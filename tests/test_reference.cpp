// The reference's invariants: white furnace, energy book, hard cases, determinism, path classes,
// reciprocity on the shipped stacks. Device runs use lavapipe in CI with the validation layer on.
#include "bin_check.h"
#include "kernel_interface.glsl"   // FAULT_*
#include "gpu_fixture.h"
#include "stack_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <tuple>

using namespace gonio;
using namespace gonio_test;

namespace {

class Reference : public GpuTest {};

// The book closes; every fraction in [0, 1] within 1e-3 (absorbed carries the zero-mean Russian-roulette balance)
// and, where the Lambertian series ran, within its noise too (its exits weigh up to S: gpu_fixture.h).
void expect_book_closes(const SimResult& r, double tol, const std::string& what) {
    const bool series =
        walk_spec(r.stack, r.options.specialised, r.options.series, r.options.orders, r.options.max_events).series;
    for (size_t a = 0; a < r.angles.size(); ++a) {
        EnergyBook e = energy_book(r, a);
        for (int c = 0; c < 3; ++c) {
            const double slack = 1e-3 + (series ? 4.5 * exit_fraction_se(r, a, c) : 0.0);
            EXPECT_NEAR(e.sum()[c], 1.0, tol) << what << " theta_i " << r.angles[a].theta_i_deg << " channel " << c;
            for (double v : {e.reflected[c], e.transmitted[c], e.absorbed[c], e.microfacet_loss[c], e.truncated[c]}) {
                EXPECT_TRUE(std::isfinite(v)) << what;
                EXPECT_GE(v, -slack) << what;
                EXPECT_LE(v, 1.0 + slack) << what;
            }
            EXPECT_LE(e.reflected[c] + e.transmitted[c], 1.0 + slack) << what;
        }
    }
}

void expect_finite(const SimResult& r, const std::string& what) {
    for (size_t a = 0; a < r.angles.size(); ++a)
        for (int side = 0; side < 2; ++side) {
            Slice s = make_slice(r, a, Side(side));
            for (size_t b = 0; b < s.f.size(); ++b)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(s.f[b][c]) && s.f[b][c] >= 0) << what << " bin " << b;
                    ASSERT_TRUE(std::isfinite(s.se[b][c]) && s.se[b][c] >= 0) << what << " bin " << b;
                }
        }
}

// White furnace: lossless stacks (smooth interfaces, no absorption, white base or slab) return all energy.
TEST_F(Reference, WhiteFurnace) {
    std::vector<Stack> stacks = {
        make_stack("clear-coat-white-lambert", {dielectric(1.5f), lambertian(glm::vec3(1.0f))}),
        make_stack("clear-slab", {dielectric(1.5f), dielectric(1.0f)}),
        make_stack("three-coats-white-lambert",
                   {dielectric(1.3f), dielectric(2.0f), dielectric(1.5f), lambertian(glm::vec3(1.0f))}),
        make_stack("slab-on-substrate", {dielectric(1.8f), dielectric(1.4f), dielectric(1.2f)}),
    };
    SimOptions o;
    o.theta_i_deg = {0, 45, 80, 89.9};
    o.paths = 1000000;
    for (auto& s : stacks)
        for (bool series : {false, true}) {
            // the full walk returns every path's energy exactly; the Lambertian series (white Lambertian stacks) in
            // expectation: its exits weigh S times the trip's, so R + T is 1 within its noise, which must also be
            // within the 1e-3 the white furnace asks for
            if (series && !walk_spec(s, true).series) continue;
            o.series = series;
            SimResult r = simulate_gpu(context(), s, o);
            for (size_t a = 0; a < r.angles.size(); ++a) {
                EnergyBook e = energy_book(r, a);
                for (int c = 0; c < 3; ++c) {
                    const double se = exit_fraction_se(r, a, c), noise = series ? 4.5 * se : 1e-6;
                    EXPECT_NEAR(e.reflected[c] + e.transmitted[c], 1.0, series ? std::min(1e-3, noise + 1e-6) : 1e-3)
                        << s.name << " theta_i " << o.theta_i_deg[a] << (series ? " (series)" : "") << " se " << se;
                    EXPECT_NEAR(e.absorbed[c] + e.microfacet_loss[c], 0.0, noise) << s.name;
                }
            }
            expect_book_closes(r, 1e-5, s.name);
        }
}

// Hard cases: finite, energy-bounded, book closes.
TEST_F(Reference, HardCases) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    std::vector<Stack> stacks = {
        make_stack("roughness-1e-4", {dielectric(1.5f, 1e-4f, glm::vec3(0.1f)), conductor(cu_n, cu_k, 1e-4f)}),
        make_stack("roughness-1", {dielectric(1.5f, 1.0f, glm::vec3(0.1f)), lambertian(glm::vec3(0.8f))}),
        make_stack("rough-slab-1", {dielectric(1.5f, 1.0f), dielectric(1.0f, 1.0f)}),
        make_stack("index-matched",
                   {dielectric(1.5f, 0.3f), dielectric(1.5f, 0.3f, glm::vec3(0.2f)), lambertian(glm::vec3(0.5f))}),
        make_stack("index-matched-exterior", {dielectric(1.0f, 0.5f), dielectric(1.0f, 0.0f)}),
        make_stack("ior-3", {dielectric(3.0f, 0.2f), lambertian(glm::vec3(0.9f))}),
        make_stack("optical-depth-50", {dielectric(1.5f, 0.1f, glm::vec3(50.0f)), lambertian(glm::vec3(0.9f))}),
        make_stack("optical-depth-0-and-50",
                   {dielectric(1.5f, 0.1f, glm::vec3(0.0f, 50.0f, 0.0f)), dielectric(1.0f, 0.1f)}),
        make_stack("conductor-k-10", {dielectric(1.5f, 0.05f), conductor(glm::vec3(1.0f), glm::vec3(10.0f), 0.3f)}),
        make_stack("tir-trap", {dielectric(3.0f, 0.0f), dielectric(1.0f, 0.5f)}),
        make_stack("tir-trap-dense-coat", {dielectric(2.5f), lambertian(glm::vec3(1.0f))}),
        make_stack("eight-layers",
                   {dielectric(1.3f, 0.1f, glm::vec3(0.05f)), dielectric(1.7f, 0.2f),
                    dielectric(1.4f, 0.0f, glm::vec3(0.1f)), dielectric(2.2f, 0.3f), dielectric(1.1f, 0.05f),
                    dielectric(1.6f, 0.0f), dielectric(2.8f, 0.4f, glm::vec3(1.0f)), conductor(cu_n, cu_k, 0.2f)}),
    };
    SimOptions o;
    o.theta_i_deg = {0, 60, 89.9};
    o.paths = 300000;
    for (auto& s : stacks)
        for (bool series :
             {true, false}) {   // where the series applies, also the walk that traces every trip (exact bounds)
            if (!series && !walk_spec(s, true).series) continue;
            SimOptions os = o;
            os.series = series;
            SimResult r = simulate_gpu(context(), s, os);
            expect_finite(r, s.name);
            expect_book_closes(r, 1e-4, s.name + (series ? "" : " (--no-series)"));
        }
    // index-matched interfaces are no interfaces: the exterior-matched stack is perfectly transparent
    {
        SimResult r = simulate_gpu(context(), stacks[4], o);
        BinGrid g(r);
        for (size_t a = 0; a < r.angles.size(); ++a) {
            EnergyBook e = energy_book(r, a);
            EXPECT_NEAR(e.transmitted.x, 1.0, 1e-6) << "index-matched stack, theta_i " << o.theta_i_deg[a];
            Slice t = make_slice(r, a, kTransmission);
            // straight through: all of it in the bin of the incident direction (at normal incidence the
            // direction is the pole, binned at phi = 0 by convention)
            size_t b = size_t(g.theta_bin(o.theta_i_deg[a])) * g.n_phi + g.phi_bin(o.theta_i_deg[a] == 0 ? 0.0 : 180.0);
            EXPECT_NEAR(t.sum[b].x, 1.0, 1e-6)
                << "index-matched stack: light must go straight through, theta_i " << o.theta_i_deg[a];
        }
    }
    // the general N-layer walk gives the same kind of answer on the eight-layer stack
    o.specialised = false;
    SimResult g = simulate_gpu(context(), stacks.back(), o);
    expect_finite(g, "general walk");
    expect_book_closes(g, 1e-4, "general walk");
}

// Same seed: identical bytes, whatever the dispatch shape. Different seed: different bytes.
TEST_F(Reference, Determinism) {
    Stack s = make_stack("plastic-like", {dielectric(1.5f, 0.05f, glm::vec3(0.05f, 0.05f, 0.3f)),
                                          lambertian(glm::vec3(0.2f, 0.6f, 0.3f))});
    SimOptions o;
    o.theta_i_deg = {30};
    o.paths = 500000;
    o.seed = 3;
    o.batch_paths = 1024 * 7;
    SimResult a = simulate_gpu(context(), s, o);
    o.batch_paths = 0;   // adaptive batches
    SimResult b = simulate_gpu(context(), s, o);
    o.paths_per_invocation = 5;   // another dispatch shape
    SimResult c = simulate_gpu(context(), s, o);
    EXPECT_TRUE(a.angles[0].raw == b.angles[0].raw);
    EXPECT_TRUE(a.angles[0].raw == c.angles[0].raw);
    EXPECT_EQ(0, std::memcmp(a.angles[0].energy, c.angles[0].energy, sizeof a.angles[0].energy));
    o.seed = 4;
    SimResult d = simulate_gpu(context(), s, o);
    EXPECT_FALSE(a.angles[0].raw == d.angles[0].raw);
}

// An opaque stack has no transmission bins (nothing is computed for effects a stack does not have): one
// histogram side, on the device, in the batch and on the CPU twin; its transmission slice reads as zero.
TEST_F(Reference, OpaqueStacksHaveNoTransmissionBins) {
    SimOptions o;
    o.theta_i_deg = {30.0};
    o.paths = 100000;
    o.orders = true;
    for (const char* f : {"stacks/plastic.toml", "stacks/metallic-paint.toml", "stacks/transparent-slab.toml"}) {
        Stack s = parse_stack_file(std::string(GONIO_SOURCE_DIR) + "/" + f);
        const uint32_t sides = s.transmissive() ? 2 : 1;
        SimOptions og = o;
        og.baked_stack =
            false;   // read from a buffer, as the batch reads it: the same bits (BatchEqualsOneRunPerStack)
        SimResult g = simulate_gpu(context(), s, og);
        SimResult b = simulate_gpu_batch(context(), {s}, {o.seed}, o)[0];
        SimResult c = simulate_cpu(s, o, 2);
        for (const SimResult* r : {&g, &b, &c}) {
            EXPECT_EQ(r->n_sides, sides) << f;
            EXPECT_EQ(r->angles[0].raw.size(), size_t(3) * sides * r->n_theta * r->n_phi * 6) << f;
        }
        EXPECT_TRUE(g.angles[0].raw == b.angles[0].raw) << f;
        double t = 0.0;
        for (const glm::dvec3& v : make_slice(g, 0, kTransmission).sum) t += v.x + v.y + v.z;
        if (sides == 1)
            EXPECT_EQ(t, 0.0) << f;
        else
            EXPECT_GT(t, 0.0) << f;
    }
}

// --orders: the classes sum exactly to the total, and the class meaning holds on a smooth coat.
TEST_F(Reference, PathClassesSumToTotal) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.0f, glm::vec3(0.1f)), lambertian(glm::vec3(0.8f))});
    SimOptions o;
    o.theta_i_deg = {20.5};
    o.paths = 400000;
    o.series = false;   // --orders traces every trip (the series sums the classes): compare with the same walk
    // exactly: the booking estimators sum a path's bookings in one bin of one class before they are quantised by
    // stochastic rounding, so with --orders a path whose bookings fall in one bin but in several classes is rounded
    // per class (measured on a rough coat: sums 2 units of 2^-12 apart in a bin); the analog walk books once
    o.branching = false;
    SimResult plain = simulate_gpu(context(), s, o);
    o.orders = true;
    SimResult split = simulate_gpu(context(), s, o);
    const size_t nb = size_t(split.n_theta) * split.n_phi * split.n_sides * 6;
    ASSERT_EQ(split.angles[0].raw.size(), 3 * nb);
    for (size_t i = 0; i < nb; ++i)
        ASSERT_EQ(plain.angles[0].raw[i],
                  split.angles[0].raw[i] + split.angles[0].raw[nb + i] + split.angles[0].raw[2 * nb + i]);
    // class 0 of a smooth coat is the mirror reflection only: exactly one non-empty bin, value F
    Slice c0 = make_slice(split, 0, kReflection, 0);
    int nonzero = 0;
    for (auto& v : c0.sum) nonzero += v.x > 0;
    EXPECT_EQ(nonzero, 1);
    // class 1 (one trip to the base and back) carries most of the diffuse energy, class 2 the rest
    double e1 = 0, e2 = 0;
    for (auto& v : make_slice(split, 0, kReflection, 1).sum) e1 += v.x;
    for (auto& v : make_slice(split, 0, kReflection, 2).sum) e2 += v.x;
    EXPECT_GT(e1, e2);
    EXPECT_GT(e2, 0.0);
}

// Reciprocity of the BRDF, f(l, v) = f(v, l), on every shipped stack: the bin at theta_B seen from incidence
// theta_A against the bin at theta_A seen from theta_B, same relative azimuth, with the incident angles at
// bin centres. Per pair: |a - b| <= 3 sqrt(se_a^2 + se_b^2) + 2% of their mean (the 2% allows for the bin
// average not being exactly reciprocal: the light direction is exact, the view direction is averaged over
// a 2.5 x 5 degree bin); the number of 3-sigma exceedances must be what chance gives (binomial bound).
TEST_F(Reference, ReciprocityOnShippedStacks) {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (auto& e : fs::directory_iterator("stacks"))
        if (e.path().extension() == ".toml") files.push_back(e.path().string());
    ASSERT_GE(files.size(), 4u);
    SimOptions o;
    o.theta_i_deg = {21.25, 51.25, 71.25};
    o.dtheta_deg = 2.5;
    o.dphi_deg = 5;
    o.paths = 4000000;
    for (auto& f : files) {
        Stack s = parse_stack_file(f);
        SimResult r = simulate_gpu(context(), s, o);
        BinGrid g(r);
        int compared = 0, over3 = 0, over_max = 0;
        double typical_rel_se = 0;
        for (size_t a = 0; a < 3; ++a)
            for (size_t b = a + 1; b < 3; ++b) {
                Slice sa = make_slice(r, a, kReflection), sb = make_slice(r, b, kReflection);
                uint32_t ta = g.theta_bin(o.theta_i_deg[a]), tb = g.theta_bin(o.theta_i_deg[b]);
                // azimuthal sectors of 6 bins (30 degrees): the same relative azimuth both ways, less noise
                for (uint32_t p0 = 0; p0 < g.n_phi; p0 += 6)
                    for (int c = 0; c < 3; ++c) {
                        double fa = 0, fb = 0, va = 0, vb = 0;
                        for (uint32_t p = p0; p < p0 + 6; ++p) {
                            size_t ia = size_t(tb) * g.n_phi + p, ib = size_t(ta) * g.n_phi + p;
                            fa += sa.f[ia][c] / 6;
                            fb += sb.f[ib][c] / 6;
                            va += std::pow(sa.se[ia][c] / 6, 2);
                            vb += std::pow(sb.se[ib][c] / 6, 2);
                        }
                        double se = std::sqrt(va + vb);
                        if (p0 == g.n_phi / 2 - 6 && c == 1) typical_rel_se = se / std::max(1e-30, 0.5 * (fa + fb));
                        double d = std::fabs(fa - fb), allow = 0.02 * 0.5 * (fa + fb);
                        compared++;
                        if (d > 3 * se + allow) over3++;
                        if (d > 5.5 * se + allow) {
                            over_max++;
                            ADD_FAILURE()
                                << f << ": f(" << o.theta_i_deg[a] << " -> " << o.theta_i_deg[b] << ", sector " << p0
                                << ") = " << fa << " but reversed " << fb << " (se " << se << ")";
                        }
                    }
            }
        double allowed = compared * 0.0027 + 4 * std::sqrt(compared * 0.0027) + 1;
        std::printf("%s: %d sector pairs compared, %d beyond 3 se + 2%% (allowed %.1f), typical relative se %.4f\n",
                    f.c_str(), compared, over3, allowed, typical_rel_se);
        EXPECT_EQ(over_max, 0) << f;
        EXPECT_LE(over3, allowed) << f;
    }
}

// Standard errors are honest: over 16 independent seeds, the spread of each bin's value matches the
// standard error each run reports. R = sum over bins of the between-seed variance / sum of the mean
// reported se^2 must be 1 (its own sampling error here is a few percent; a wrong factor of 2 in the
// variance, or using the sum instead of the mean, moves it far outside [0.85, 1.15]).
TEST_F(Reference, StandardErrorsAreHonest) {
    Stack s = make_stack("rough-plastic", {dielectric(1.5f, 0.3f, glm::vec3(0.1f, 0.2f, 0.4f)),
                                           lambertian(glm::vec3(0.8f, 0.5f, 0.3f))});
    SimOptions o;
    o.theta_i_deg = {40};
    o.paths = 500000;
    o.dtheta_deg = 5;
    o.dphi_deg = 10;
    const int seeds = 16;
    std::vector<Slice> runs;
    for (int k = 0; k < seeds; ++k) {
        o.seed = 100 + k;
        SimResult r = simulate_gpu(context(), s, o);
        runs.push_back(make_slice(r, 0, kReflection));
    }
    SimOptions geometry;   // only the bins' geometry is read from this run
    geometry.theta_i_deg = o.theta_i_deg;
    geometry.paths = 1000;
    geometry.dtheta_deg = o.dtheta_deg;
    geometry.dphi_deg = o.dphi_deg;
    BinGrid g(simulate_gpu(context(), s, geometry));
    double sum_var = 0, sum_se2 = 0;
    int bins = 0;
    for (size_t b = 0; b < runs[0].f.size(); ++b)
        for (int c = 0; c < 3; ++c) {
            double mean = 0, se2 = 0;
            for (auto& r : runs) {
                mean += r.f[b][c] / seeds;
                se2 += r.se[b][c] * r.se[b][c] / seeds;
            }
            double omega = g.projected_solid_angle(uint32_t(b / g.n_phi));
            if (mean * omega * double(o.paths) < 100) continue;   // too few paths for a meaningful se
            double var = 0;
            for (auto& r : runs) var += (r.f[b][c] - mean) * (r.f[b][c] - mean) / (seeds - 1);
            sum_var += var;
            sum_se2 += se2;
            bins++;
        }
    double ratio = sum_var / sum_se2;
    std::printf("standard-error honesty: %d bin-channels, between-seed variance / reported se^2 = %.3f\n", bins, ratio);
    EXPECT_GT(bins, 300);
    EXPECT_GT(ratio, 0.85);
    EXPECT_LT(ratio, 1.15);
}

}   // namespace

namespace {

// A batch of stacks in shared dispatches (gonio sweep) gives, stack for stack, the very integer sums of one
// run per stack with its seed and the stack read from a buffer as the batch does (--no-baked-stack): specialised walk for stacks of one shape, general walk when their rough or
// absorbing layers differ.
TEST_F(Reference, BatchEqualsOneRunPerStack) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    std::vector<Stack> same = {
        make_stack("a", {dielectric(1.5f, 0.1f, glm::vec3(0.1f)), conductor(cu_n, cu_k, 0.2f)}),
        make_stack("b", {dielectric(1.3f, 0.4f, glm::vec3(0.5f)), conductor(cu_n, cu_k, 0.05f)}),
        make_stack("c", {dielectric(2.0f, 0.02f, glm::vec3(0.01f)), conductor(cu_n, cu_k, 0.6f)})};
    // the general walk's batch: a smooth stack, and one whose coat scatters (the walk then carries the free-flight
    // code for all three, and the two that do not scatter must not notice)
    Layer hazy = dielectric(1.5f, 0.05f, glm::vec3(0.8f, 1.0f, 1.2f));
    hazy.scattering_albedo = glm::vec3(0.9f, 0.7f, 0.5f);
    hazy.phase_g = 0.6f;
    std::vector<Stack> mixed = {same[0], make_stack("smooth", {dielectric(1.5f, 0.0f), conductor(cu_n, cu_k, 0.0f)}),
                                make_stack("scattering", {hazy, conductor(cu_n, cu_k, 0.2f)})};
    for (bool specialised : {true, false}) {
        const std::vector<Stack>& stacks = specialised ? same : mixed;
        std::vector<uint32_t> seeds;
        for (size_t i = 0; i < stacks.size(); ++i) seeds.push_back(uint32_t(100 + 7 * i));
        SimOptions o;
        o.theta_i_deg = {0, 50};
        o.paths = 150000;
        o.specialised = specialised;
        std::vector<SimResult> batch = simulate_gpu_batch(context(), stacks, seeds, o);
        ASSERT_EQ(batch.size(), stacks.size());
        for (size_t i = 0; i < stacks.size(); ++i) {
            SimOptions oi = o;
            oi.seed = seeds[i];
            oi.baked_stack = false;   // a batch reads its stacks from a buffer: so must the one run, to round alike
            SimResult one = simulate_gpu(context(), stacks[i], oi);
            for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
                EXPECT_EQ(batch[i].angles[a].paths, one.angles[a].paths);
                EXPECT_TRUE(batch[i].angles[a].raw == one.angles[a].raw) << stacks[i].name << " angle " << a;
                for (int k = 0; k < 9; ++k)
                    EXPECT_EQ(batch[i].angles[a].energy[k], one.angles[a].energy[k]) << stacks[i].name;
            }
        }
    }
    // the specialised walk refuses stacks of different specialisations rather than tracing them wrongly
    SimOptions o;
    o.paths = 1000;
    EXPECT_THROW(simulate_gpu_batch(context(), mixed, {1, 2, 3}, o), std::invalid_argument);
}

// --rse in a batch (gonio sweep with rse = R): each stack stops at the checkpoint where its own simulate_gpu
// --rse run stops, with the same paths, bits and stopped_by, while the others go on in the same dispatches.
TEST_F(Reference, BatchWithRseStopsEachStackAsItsOwnRun) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    // a rough wide lobe needs more paths to reach the target than a narrow one whose few bins fill fast
    std::vector<Stack> stacks = {make_stack("narrow", {dielectric(1.5f, 0.05f), conductor(cu_n, cu_k, 0.05f)}),
                                 make_stack("medium", {dielectric(1.5f, 0.3f), conductor(cu_n, cu_k, 0.3f)}),
                                 make_stack("wide", {dielectric(1.5f, 0.8f), conductor(cu_n, cu_k, 0.9f)})};
    std::vector<uint32_t> seeds = {11, 12, 13};
    SimOptions o;
    o.theta_i_deg = {20};
    o.dtheta_deg = 5;
    o.dphi_deg = 10;
    o.rse_target = 0.08;
    o.rse_quantile = 1.0;   // the worst bin (the case's stacks stop at different checkpoints on it)
    o.paths = 1u << 22;   // the cap: checkpoints 2^20, 2^21, 2^22
    std::vector<SimResult> batch = simulate_gpu_batch(context(), stacks, seeds, o);
    std::set<uint64_t> distinct;
    for (size_t i = 0; i < stacks.size(); ++i) {
        SimOptions oi = o;
        oi.seed = seeds[i];
        oi.baked_stack = false;   // as the batch: the stack read from a buffer
        SimResult one = simulate_gpu(context(), stacks[i], oi);
        const AngleResult &b = batch[i].angles[0], &r = one.angles[0];
        std::printf("%-8s paths %llu stopped by %s, worst rse %.4f\n", stacks[i].name.c_str(),
                    (unsigned long long)b.paths, b.stopped_by.c_str(), b.worst_rse);
        EXPECT_EQ(b.paths, r.paths) << stacks[i].name;
        EXPECT_EQ(b.stopped_by, r.stopped_by) << stacks[i].name;
        EXPECT_EQ(b.worst_rse, r.worst_rse) << stacks[i].name;
        EXPECT_TRUE(b.raw == r.raw) << stacks[i].name;
        for (int k = 0; k < 9; ++k) EXPECT_EQ(b.energy[k], r.energy[k]) << stacks[i].name;
        if (b.stopped_by == "rse") { EXPECT_LE(b.worst_rse, o.rse_target); }
        distinct.insert(b.paths);
    }
    // the case is chosen so that the stacks stop at different checkpoints (else it would not test the mask)
    EXPECT_GE(distinct.size(), 2u);
}

// Two runs of the same angles, angle for angle: the same paths, integer sums, energy book and stopping point.
void expect_same_angles(const SimResult& a, const SimResult& b, const std::string& what) {
    ASSERT_EQ(a.angles.size(), b.angles.size()) << what;
    for (size_t i = 0; i < a.angles.size(); ++i) {
        const AngleResult &x = a.angles[i], &y = b.angles[i];
        const std::string at = what + " theta_i " + std::to_string(x.theta_i_deg);
        EXPECT_EQ(x.theta_i_deg, y.theta_i_deg) << at;
        EXPECT_EQ(x.paths, y.paths) << at;
        EXPECT_EQ(x.stopped_by, y.stopped_by) << at;
        EXPECT_EQ(x.worst_rse, y.worst_rse) << at;
        EXPECT_TRUE(x.raw == y.raw) << at << ": histogram differs";
        EXPECT_EQ(0, std::memcmp(x.energy, y.energy, sizeof x.energy)) << at << ": energy book differs";
    }
}

// Paths per stack in a batch (a spectral run's passes): each stack's result is its own simulate_gpu run with its
// paths, without --rse and with it (narrow: a cap below the first checkpoint; medium: stopped by its target at the
// first; wide: a cap between the second and third, its target not met).
TEST_F(Reference, BatchWithPathsPerStackIsEachStacksOwnRun) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    std::vector<Stack> stacks = {make_stack("narrow", {dielectric(1.5f, 0.05f), conductor(cu_n, cu_k, 0.05f)}),
                                 make_stack("medium", {dielectric(1.5f, 0.3f), conductor(cu_n, cu_k, 0.3f)}),
                                 make_stack("wide", {dielectric(1.5f, 0.8f), conductor(cu_n, cu_k, 0.9f)})};
    const std::vector<uint32_t> seeds = {21, 22, 23};
    for (bool rse : {false, true}) {
        SimOptions o;
        o.theta_i_deg = rse ? std::vector<double>{20} : std::vector<double>{0, 50};
        o.dtheta_deg = 5;
        o.dphi_deg = 10;
        if (rse) {
            o.rse_target = 0.08;
            o.rse_quantile = 1.0;
        }
        const std::vector<uint64_t> paths = rse ? std::vector<uint64_t>{300000, 1u << 22, (1u << 21) + 5000}
                                                : std::vector<uint64_t>{40000, 150001, 90000};
        o.paths = 1000;   // not used where each stack has its own
        std::vector<SimResult> batch = simulate_gpu_batch(context(), stacks, seeds, o, paths);
        for (size_t i = 0; i < stacks.size(); ++i) {
            SimOptions oi = o;
            oi.seed = seeds[i];
            oi.paths = paths[i];
            oi.baked_stack = false;   // as the batch: the stack read from a buffer
            const SimResult one = simulate_gpu(context(), stacks[i], oi);
            EXPECT_EQ(batch[i].options.paths, paths[i]);
            expect_same_angles(batch[i], one, stacks[i].name + (rse ? " (--rse)" : ""));
            if (rse)
                std::printf("%-8s cap %llu: %llu paths, stopped by %s\n", stacks[i].name.c_str(),
                            (unsigned long long)paths[i], (unsigned long long)batch[i].angles[0].paths,
                            batch[i].angles[0].stopped_by.c_str());
        }
    }
    SimOptions o;
    o.paths = 1000;
    EXPECT_THROW(simulate_gpu_batch(context(), stacks, seeds, o, {1000, 2000}), std::invalid_argument);
}

// Incident angles side by side in shared dispatches (simulate_gpu's default: workgroup row y traces angle y) give,
// angle for angle, the bytes of one angle at a time (angles_per_dispatch 1, how angles ran before): a path's random
// numbers depend on (seed, path index, angle index) only. Light from a dense exterior (IOR 2) onto a rarer coat totally
// reflects beyond 30 degrees; 89.9 degrees is grazing; dispatches of fixed size fold their staging before it could
// carry (more than 2^20 paths per angle); a transmissive stack with path classes on fewer slots than angles (angles
// wait for a slot); --rse stops angles at different rounds while the others go on.
TEST_F(Reference, AnglesSideBySideEqualOneAngleAtATime) {
    const glm::vec3 cu_n(0.27f, 0.68f, 1.22f), cu_k(3.6f, 2.6f, 2.3f);
    Stack dense =
        make_stack("dense-exterior", {dielectric(1.0f, 0.1f, glm::vec3(0.1f)), conductor(cu_n, cu_k, 0.3f)}, 2.0f);
    SimOptions o;
    o.theta_i_deg = {0, 20, 45, 70, 89.9};
    o.paths = 1100000;
    o.batch_paths = 1024 * 293;   // the fourth dispatch would pass 2^20 paths in the staging: folded first
    o.seed = 5;
    SimResult side = simulate_gpu(context(), dense, o);
    o.angles_per_dispatch = 1;
    o.batch_paths = 1024 * 97;   // and other dispatches: the bytes do not depend on them either
    SimResult turn = simulate_gpu(context(), dense, o);
    expect_same_angles(side, turn, "dense exterior");

    Stack slab = make_stack("slab", {dielectric(1.5f, 0.2f, glm::vec3(0.2f)), dielectric(1.0f, 0.4f)});
    SimOptions t;
    t.theta_i_deg = {89.9, 0, 60};
    t.paths = 150000;
    t.orders = true;
    t.angles_per_dispatch = 2;
    SimResult two = simulate_gpu(context(), slab, t);
    t.angles_per_dispatch = 1;
    expect_same_angles(two, simulate_gpu(context(), slab, t), "slab, two slots");

    SimOptions r;   // as BatchWithRseStopsEachStackAsItsOwnRun, over angles of one stack
    r.theta_i_deg = {0, 60, 85};
    r.dtheta_deg = 5;
    r.dphi_deg = 10;
    r.rse_target = 0.08;
    r.rse_quantile = 1.0;
    r.paths = 1u << 21;   // the cap: checkpoints 2^20, 2^21
    Stack rough = make_stack("rough", {dielectric(1.5f, 0.3f), conductor(cu_n, cu_k, 0.3f)});
    // the default walk (the booking estimators on this rough coat over a rough metal: the entry's both branches and
    // an exit estimate) the same
    SimResult rse_default = simulate_gpu(context(), rough, r);
    ASSERT_TRUE(rse_default.walk.entry_branch) << "the case must exercise the estimators";
    r.angles_per_dispatch = 1;
    expect_same_angles(rse_default, simulate_gpu(context(), rough, r), "--rse, the default walk");
    r.angles_per_dispatch = 0;
    r.branching = false;   // the analog walk, whose angles reach the target at different rounds (the mask is tested)
    SimResult rse_side = simulate_gpu(context(), rough, r);
    r.angles_per_dispatch = 1;
    SimResult rse_turn = simulate_gpu(context(), rough, r);
    expect_same_angles(rse_side, rse_turn, "--rse");
    std::set<uint64_t> distinct;
    for (const AngleResult& a : rse_side.angles) {
        std::printf("theta_i %4.1f: %llu paths, stopped by %s, worst rse %.4f\n", a.theta_i_deg,
                    (unsigned long long)a.paths, a.stopped_by.c_str(), a.worst_rse);
        distinct.insert(a.paths);
    }
    EXPECT_GE(distinct.size(), 2u) << "the angles should stop at different rounds (else the case tests no mask)";
}

// Checkpoints of angles side by side (a state after every dispatch) resume to the bytes of one unbroken run, from
// any of them, side by side or one angle at a time.
TEST_F(Reference, AnglesSideBySideResumeFromAnyCheckpoint) {
    Stack s = make_stack("coat", {dielectric(1.5f, 0.1f, glm::vec3(0.1f)), lambertian(glm::vec3(0.7f))});
    SimOptions o;
    o.theta_i_deg = {10, 50, 89.9};
    o.paths = 150000;
    o.batch_paths = 1024 * 20;
    SimResult whole = simulate_gpu(context(), s, o);
    std::vector<SimResult> states;
    SimOptions c = o;
    c.checkpoint_seconds = 0;   // after every dispatch
    c.on_checkpoint = [&](const SimResult& partial) { states.push_back(partial); };
    c.paths = 100000;   // a shorter first run, then resumed to o.paths
    SimResult shorter = simulate_gpu(context(), s, c);
    ASSERT_GE(states.size(), 2u);
    states.push_back(shorter);
    for (size_t k : {size_t(0), states.size() / 2, states.size() - 1})
        for (uint32_t per_dispatch : {0u, 1u}) {
            SimOptions more = o;
            more.angles_per_dispatch = per_dispatch;
            SimResult resumed = simulate_gpu(context(), s, more, &states[k]);
            expect_same_angles(whole, resumed, "resumed from state " + std::to_string(k));
        }
}

// A state file whose run booked with other estimators than this build would (an earlier version's: one exit estimate
// through a slab's base) is refused with both, not continued with a mixture.
TEST_F(Reference, ResumeRefusesAnotherBuildsEstimators) {
    const Stack s =
        make_stack("rough-slab", {dielectric(1.5f, 0.001f, glm::vec3(0.05f, 0.1f, 0.5f)), dielectric(1.0f, 0.2f)});
    SimOptions o;
    o.theta_i_deg = {30};
    o.paths = 20000;
    SimResult earlier = simulate_gpu(context(), s, o);
    ASSERT_GT(earlier.walk.exit_estimates, 1u);
    o.paths = 40000;
    EXPECT_NO_THROW(check_resumable(earlier, s, o));
    earlier.walk.exit_estimates = 1;
    try {
        check_resumable(earlier, s, o);
        ADD_FAILURE() << "resumed a run of other estimators";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("booked with 1 exit estimate per path, this gonio with"),
                  std::string::npos)
            << e.what();
    }
}

// The stack's parameters compiled into the shader (the default for specialised walks of one or two layers,
// stack_constants.glsl) against the same run reading them from the uniform buffer: the same paths, so the sums may
// differ only where the compiler's folding of the constants rounds a weight differently in its last bits (a
// dithered fixed-point quantum here and there). A wrong constant (a channel or a layer swapped, a value off by
// 1e-3) moves the sums by far more than the bound. Every shipped and hard stack of one or two layers, four angles.
TEST_F(Reference, BakedStackMatchesUniformStack) {
    std::vector<std::string> files;
    for (const char* dir : {"/stacks", "/stacks/hard"})
        for (const auto& e : std::filesystem::directory_iterator(std::string(GONIO_SOURCE_DIR) + dir))
            if (e.path().extension() == ".toml") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    int tested = 0;
    for (const std::string& f : files) {
        Stack s = parse_stack_file(f);
        if (!can_bake_stack(walk_spec(s, true))) continue;
        SimOptions o;
        o.theta_i_deg = {0, 40, 75, 89.9};
        o.paths = 200000;
        o.seed = 3;
        SimResult baked = simulate_gpu(context(), s, o);
        o.baked_stack = false;
        SimResult uniform = simulate_gpu(context(), s, o);
        for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
            const AngleResult &x = baked.angles[a], &y = uniform.angles[a];
            ASSERT_EQ(x.raw.size(), y.raw.size());
            double sum = 0, diff = 0;
            for (size_t i = 0; i < x.raw.size(); ++i) {
                sum += double(x.raw[i]);
                diff += std::fabs(double(x.raw[i]) - double(y.raw[i]));
            }
            EXPECT_LE(diff, 1e-5 * sum) << s.name << " theta_i " << o.theta_i_deg[a];
            for (int k = 0; k < 9; ++k)   // the energy book: within 1e-5 of the paths' energy
                EXPECT_LE(std::fabs(double(x.energy[k] - y.energy[k])), 1e-5 * kEnergyScale * double(o.paths))
                    << s.name << " theta_i " << o.theta_i_deg[a] << " entry " << k;
        }
        ++tested;
    }
    EXPECT_GE(tested, 15);
}

// The booking estimators (the entry's both branches, the exit estimate; docs/PHYSICS.md, "Booking estimators")
// against the analog walk (--no-branching), bin by bin: the two runs' difference within their joint noise alone (the
// rule of bin_check.h with no relative slack: two Monte Carlo runs differ by noise, not by quadrature), on stacks
// where each applies: a near-smooth coat over a rough conductor and a rough coat over a near-mirror (both), a
// scattering coat (the entry alone), slabs of a near-smooth top and a rough bottom and of a rough top and a smooth
// bottom (the exit estimates through the base, both sides), at normal, oblique and grazing incidence; and the energy
// book the same within its noise. fault: a FAULT_* the comparison must catch (the negative controls).
struct AnalogComparison {
    BinCheck bins;
    int energy_off = 0;   // energy-book entries beyond 5 se
    std::string energy_worst;
    bool agrees() const { return within_noise(bins) && energy_off == 0; }
};

AnalogComparison compare_with_analog(const Stack& s, bool entry_branch, uint32_t exit_estimates,
                                     uint32_t fault = FAULT_NONE) {
    SimOptions o;
    o.theta_i_deg = {0.0, 45.0, 80.0};
    o.paths = 2000000;
    o.dtheta_deg = 2;
    o.dphi_deg = 4;
    o.seed = 5;
    o.fault_for_tests = fault;
    const SimResult b = simulate_gpu(context(), s, o);
    EXPECT_EQ(b.walk.entry_branch, entry_branch) << s.name;
    EXPECT_EQ(b.walk.exit_estimates, exit_estimates) << s.name;
    o.branching = false;
    o.fault_for_tests = FAULT_NONE;
    o.seed = 6;
    const SimResult a = simulate_gpu(context(), s, o);
    EXPECT_FALSE(a.walk.entry_branch || a.walk.exit_estimates > 0);
    BinGrid g(a);
    AnalogComparison r;
    const double N = double(o.paths);
    for (size_t k = 0; k < o.theta_i_deg.size(); ++k) {
        for (int side = 0; side < int(a.n_sides); ++side) {
            const Slice sa = make_slice(a, k, Side(side)), sb = make_slice(b, k, Side(side));
            for (size_t bin = 0; bin < sa.f.size(); ++bin)
                for (int c = 0; c < 3; ++c) {
                    const double omega = g.projected_solid_angle(uint32_t(bin / g.n_phi));
                    if (sa.f[bin][c] * omega * N < 100) continue;   // se unreliable
                    char where[160];
                    std::snprintf(where, sizeof where, "%s theta_i %g side %d bin %zu ch %d", s.name.c_str(),
                                  o.theta_i_deg[k], side, bin, c);
                    check_value(r.bins, sb.f[bin][c], std::hypot(sa.se[bin][c], sb.se[bin][c]), sa.f[bin][c], where,
                                0.0);
                }
        }
        const EnergyBook ea = energy_book(a, k), eb = energy_book(b, k);
        // the analog's exit fraction has exit_fraction_se (both sides); the estimators' paths book several bins,
        // whose cross terms that se leaves out: bounded by Var <= max(total) E[total] <= 2 E[total] per path. A loss
        // per path is in [0, 1]: variance at most 1/4 in each run.
        for (int c = 0; c < 3; ++c) {
            const double left = eb.reflected[c] + eb.transmitted[c], left_a = ea.reflected[c] + ea.transmitted[c];
            const double se = std::hypot(exit_fraction_se(a, k, c), std::sqrt(2.0 * left / N));
            const double loss_se = std::sqrt(0.5 / N);
            for (auto [x, y, e, what] :
                 {std::tuple{left, left_a, se, "light that left"},
                  std::tuple{eb.microfacet_loss[c], ea.microfacet_loss[c], loss_se, "microfacet loss"}})
                if (std::fabs(x - y) > 5.0 * e) {
                    ++r.energy_off;
                    r.energy_worst = std::string(what) + " at " + std::to_string(o.theta_i_deg[k]) + ": " +
                                     std::to_string(x) + " against the analog's " + std::to_string(y);
                }
            EXPECT_NEAR(eb.sum()[c], 1.0, 1e-6) << s.name;
        }
    }
    return r;
}

void expect_agrees_with_analog(const Stack& s, bool entry_branch, uint32_t exit_estimates) {
    const AnalogComparison r = compare_with_analog(s, entry_branch, exit_estimates);
    expect_matches(r.bins, s.name + ": the booking estimators against the analog walk");
    EXPECT_EQ(r.energy_off, 0) << s.name << ": the energy book differs from the analog's: " << r.energy_worst;
}

const glm::vec3 kMetalN(1.45f), kMetalK(3.6f, 2.6f, 2.3f);

Stack glossy_coat_rough_metal() {
    return make_stack("glossy-coat-rough-metal",
                      {dielectric(1.5f, 0.001f, glm::vec3(0.1f)), conductor(kMetalN, kMetalK, 0.2f)});
}

TEST_F(Reference, BookingEstimatorsAgreeWithTheAnalogWalk) {
    Layer hazy = dielectric(1.5f, 0.05f, glm::vec3(0.3f));
    hazy.scattering_albedo = glm::vec3(0.9f);
    hazy.phase_g = 0.5f;
    expect_agrees_with_analog(glossy_coat_rough_metal(), true, 1);
    expect_agrees_with_analog(
        make_stack("rough-coat-mirror", {dielectric(1.5f, 0.2f, glm::vec3(0.1f)), conductor(kMetalN, kMetalK, 0.001f)}),
        true, 1);
    expect_agrees_with_analog(make_stack("hazy-coat-metal", {hazy, conductor(kMetalN, kMetalK, 0.2f)}), true, 0);
    expect_agrees_with_analog(
        make_stack("rough-slab", {dielectric(1.5f, 0.001f, glm::vec3(0.05f, 0.1f, 0.5f)), dielectric(1.0f, 0.2f)}),
        false, 6);
    // through a smooth base every fresh estimate would be the same refraction: one
    expect_agrees_with_analog(
        make_stack("rough-top-slab", {dielectric(1.5f, 0.2f, glm::vec3(0.05f, 0.1f, 0.5f)), dielectric(1.0f, 0.0f)}),
        false, 1);
}

// The negative control of the comparison above: the entry's reflected branch booked 2% heavy (the size of bias the
// 0.5% slack of a closed-form check would let through in a bright bin) must fail it.
TEST_F(Reference, AnalogComparisonCatchesAHeavyEntryBranch) {
    const AnalogComparison r = compare_with_analog(glossy_coat_rough_metal(), true, 1, FAULT_ENTRY_BRANCH_HEAVY);
    std::printf(
        "entry branch 2%% heavy: %d bin-channels, %d beyond 3 se (allowed %.1f), %d beyond 5.5 se, worst z "
        "%.1f at %s\n",
        r.bins.compared, r.bins.over3, allowed_over3(r.bins), r.bins.over_max, r.bins.worst_z, r.bins.worst.c_str());
    EXPECT_FALSE(r.agrees()) << "a 2% heavy entry branch passed the comparison with the analog walk";
}

// A glossy coat over a near-mirror (many bins), a coat over a conductor both of roughness 10^-4, where the entry's
// reflection, the path's exit, its later exits and the exit estimate all fall in the specular bins (booked apart,
// their squares would leave out every cross term), and a slab of two such interfaces, whose six exit estimates and
// the path's own exit fall in its transmitted specular bin. The statistic: the mean over bin-channels of each one's
// between-seed variance over its mean reported se^2; its own noise about sqrt(2 / (seeds - 1)) over the square root
// of the independent bins (channels are correlated): 0.01 for the first (549 bin-channels, 16 seeds), at most 0.06
// for the others (over 400 bin-channels at 9 angles, most of them neighbours of the specular bins; 64 and 32 seeds).
double between_seed_over_reported(const Stack& s, SimOptions o, int seeds, Side side = kReflection,
                                  bool entry_branch = true) {
    std::vector<std::vector<Slice>> runs(o.theta_i_deg.size());
    SimResult last;
    for (int k = 0; k < seeds; ++k) {
        o.seed = 300 + k;
        last = simulate_gpu(context(), s, o);
        EXPECT_EQ(last.walk.entry_branch, entry_branch);
        EXPECT_GT(last.walk.exit_estimates, 0u);
        for (size_t a = 0; a < o.theta_i_deg.size(); ++a) runs[a].push_back(make_slice(last, a, side));
    }
    BinGrid g(last);
    double sum_ratio = 0;
    int bins = 0;
    for (const auto& angle : runs)
        for (size_t b = 0; b < angle[0].f.size(); ++b)
            for (int c = 0; c < 3; ++c) {
                double mean = 0, se2 = 0;
                for (auto& r : angle) {
                    mean += r.f[b][c] / seeds;
                    se2 += r.se[b][c] * r.se[b][c] / seeds;
                }
                double omega = g.projected_solid_angle(uint32_t(b / g.n_phi));
                if (mean * omega * double(o.paths) < 100) continue;
                double var = 0;
                for (auto& r : angle) var += (r.f[b][c] - mean) * (r.f[b][c] - mean) / (seeds - 1);
                sum_ratio += var / se2;
                bins++;
            }
    std::printf("%s: %d bin-channels, mean of between-seed variance / reported se^2 = %.3f\n", s.name.c_str(), bins,
                sum_ratio / bins);
    EXPECT_GT(bins, 25) << s.name;
    return sum_ratio / bins;
}

TEST_F(Reference, StandardErrorsAreHonestWithTheBookingEstimators) {
    const glm::vec3 nc = kMetalN, kc = kMetalK;
    SimOptions o;
    o.theta_i_deg = {30};
    o.paths = 200000;
    const double glossy = between_seed_over_reported(
        make_stack("glossy-coat-mirror", {dielectric(1.5f, 0.03f, glm::vec3(0.1f)), conductor(nc, kc, 0.03f)}), o, 16);
    EXPECT_GT(glossy, 0.9);
    EXPECT_LT(glossy, 1.1);
    o.theta_i_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80};
    o.paths = 50000;
    const double smooth = between_seed_over_reported(
        make_stack("near-smooth-coat-mirror", {dielectric(1.5f, 1e-4f, glm::vec3(0.1f)), conductor(nc, kc, 1e-4f)}), o,
        64);
    EXPECT_GT(smooth, 0.75);
    EXPECT_LT(smooth, 1.25);
    const double slab = between_seed_over_reported(
        make_stack("near-smooth-slab", {dielectric(1.5f, 1e-4f, glm::vec3(0.1f)), dielectric(1.0f, 1e-4f)}), o, 32,
        kTransmission, false);
    EXPECT_GT(slab, 0.75);
    EXPECT_LT(slab, 1.25);
}

// The negative control of the test above: a path's bookings in one bin squared apart (their cross terms left out)
// must show as a between-seed variance well above the reported se^2 on the near-smooth coat over a mirror, where the
// entry's reflection, the path's exit and the exit estimate share the specular bins (there the squares apart fall
// below the mean's square: a reported se of 0, a ratio of infinity, within 8 seeds).
TEST_F(Reference, SeHonestyCatchesBookingsSquaredApart) {
    SimOptions o;
    o.theta_i_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80};
    o.paths = 50000;
    o.fault_for_tests = FAULT_BOOKINGS_SQUARED_APART;
    const double ratio = between_seed_over_reported(
        make_stack("near-smooth-coat-mirror",
                   {dielectric(1.5f, 1e-4f, glm::vec3(0.1f)), conductor(kMetalN, kMetalK, 1e-4f)}),
        o, 8);
    EXPECT_GT(ratio, 1.25) << "bookings squared apart passed the standard errors' honesty check";
}

}   // namespace

// An incident azimuth turns the light (bins.glsl incident_direction): on isotropic stacks, a run at phi_i = 90 degrees
// is the run at phi_i = 0 with its phi bins turned by 90 degrees, bin by bin within the two runs' joint noise (the rule
// of bin_check.h, no slack), on the device and on the CPU twin, and the batch's bits are one run's; the same bins not
// turned differ far beyond the noise (the azimuth reaches the walk); the energy book is the same within its noise.
BinCheck turned_bins(const SimResult& at, const SimResult& plane, uint32_t shift, size_t angle) {
    BinCheck check;
    BinGrid g(plane);
    const double paths = double(std::min(at.angles[angle].paths, plane.angles[angle].paths));
    for (int side = 0; side < int(plane.n_sides); ++side) {
        const Slice a = make_slice(at, angle, Side(side)), p = make_slice(plane, angle, Side(side));
        for (uint32_t t = 0; t < g.n_theta; ++t)
            for (uint32_t q = 0; q < g.n_phi; ++q) {
                const size_t b = size_t(t) * g.n_phi + q, b0 = size_t(t) * g.n_phi + (q + g.n_phi - shift) % g.n_phi;
                for (int c = 0; c < 3; ++c) {
                    if (p.f[b0][c] * g.projected_solid_angle(t) * paths < 100) continue;   // se unreliable
                    char where[128];
                    std::snprintf(where, sizeof where, "%s side %d theta bin %u phi bin %u ch %d",
                                  plane.stack.name.c_str(), side, t, q, c);
                    check_value(check, a.f[b][c], std::hypot(a.se[b][c], p.se[b0][c]), p.f[b0][c], where, 0.0);
                }
            }
    }
    return check;
}

TEST_F(Reference, AnIncidentAzimuthTurnsTheBins) {
    const Stack metal = glossy_coat_rough_metal();
    const Stack plastic = parse_stack_file(std::string(GONIO_SOURCE_DIR) + "/stacks/plastic.toml");
    const Stack slab =
        make_stack("rough-slab", {dielectric(1.5f, 0.2f, glm::vec3(0.05f, 0.1f, 0.5f)), dielectric(1.0f, 0.1f)});
    for (const Stack* s : {&metal, &plastic, &slab}) {
        SimOptions o;
        o.theta_i_deg = {40.0};
        o.paths = 1000000;
        o.dtheta_deg = 3;
        o.dphi_deg = 6;
        o.seed = 7;
        const SimResult plane = simulate_gpu(context(), *s, o);
        o.phi_i_deg = 90.0;
        o.seed = 8;
        const SimResult turned = simulate_gpu(context(), *s, o);
        EXPECT_EQ(turned.angles[0].phi_i_deg, 90.0);
        const uint32_t shift = uint32_t(90.0 / o.dphi_deg);
        expect_matches(turned_bins(turned, plane, shift, 0), s->name + ": phi_i 90 against phi_i 0 turned by 90");
        EXPECT_FALSE(within_noise(turned_bins(turned, plane, 0, 0)))
            << s->name << ": the azimuth did not turn the bins";
        const EnergyBook e0 = energy_book(plane, 0), e90 = energy_book(turned, 0);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(e90.reflected[c] + e90.transmitted[c], e0.reflected[c] + e0.transmitted[c],
                        5.0 * std::sqrt(2.0 * 2.0 / double(o.paths)))
                << s->name;
        // the batch (a uniform stack) is one run's bits; the CPU twin turns the bins as the device does
        o.baked_stack = false;
        const SimResult uniform = simulate_gpu(context(), *s, o);
        EXPECT_TRUE(simulate_gpu_batch(context(), {*s}, {o.seed}, o)[0].angles[0].raw == uniform.angles[0].raw)
            << s->name;
        o.paths = 200000;
        o.seed = 9;
        expect_matches(turned_bins(simulate_cpu(*s, o, 2), plane, shift, 0), s->name + ": the CPU twin at phi_i 90");
    }
}
