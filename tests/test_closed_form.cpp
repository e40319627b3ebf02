// The reference against exact answers: smooth interfaces have closed forms (tests/exact.h). Each case runs
// on the device (lavapipe in CI, validation layer on) and on the CPU twin, under the acceptance rule of
// tests/bin_check.h (bin by bin, a binomial bound on the 3-se exceedances).
#include "bin_check.h"
#include "exact.h"

#include <cstdio>
#include <functional>
#include <thread>

using namespace gonio;
using namespace gonio_test;

namespace {

// Smooth absorbing coat over a Lambertian base: the whole BRDF, bin by bin.
void coat_over_lambertian(bool cpu) {
    const glm::vec3 tau(0.0f, 0.3f, 1.0f), rho(0.9f, 0.5f, 0.7f);
    const double n = 1.5;
    Stack s = make_stack("coat-lambert", {dielectric(1.5f, 0.0f, tau), lambertian(rho)});
    SimOptions o;
    o.theta_i_deg = {30.5, 70.5};
    o.paths = cpu ? 3000000 : 8000000;
    o.dtheta_deg = 3;
    o.dphi_deg = 6;
    o.seed = 11;
    SimResult r = run(s, o, cpu);
    BinGrid g(r);
    BinCheck check;
    for (size_t a = 0; a < r.angles.size(); ++a) {
        double ci = std::cos(o.theta_i_deg[a] * M_PI / 180);
        Slice sl = make_slice(r, a, kReflection);
        uint32_t mt = g.theta_bin(o.theta_i_deg[a]), mp = g.phi_bin(180.0);
        std::vector<exact::CoatLambert> ex;
        for (int c = 0; c < 3; ++c) ex.emplace_back(1.0, n, tau[c], rho[c]);
        // exact bin average of the diffuse part: integral of f cos over the bin / projected solid angle
        auto exact_bin = [&](uint32_t t, uint32_t p, int c) {
            double lo = g.theta_lo(t) * M_PI / 180, hi = g.theta_hi(t) * M_PI / 180, acc = 0;
            const int K = 64;
            for (int k = 0; k < K; ++k) {
                double th = lo + (k + 0.5) * (hi - lo) / K;
                acc += ex[c].diffuse(ci, std::cos(th)) * std::cos(th) * std::sin(th);
            }
            double omega = g.projected_solid_angle(t);
            double fd = acc * (hi - lo) / K * (g.dphi_deg * M_PI / 180) / omega;
            return fd + ((t == mt && p == mp) ? ex[c].specular(ci) / omega : 0.0);
        };
        compare_bins(check, sl, g, o.paths, 3, exact_bin, "theta_i " + std::to_string(o.theta_i_deg[a]),
                     std::min({rho.x, rho.y, rho.z}));
        // nothing may leave through the bottom of an opaque stack
        for (auto& v : make_slice(r, a, kTransmission).sum) EXPECT_EQ(v, glm::dvec3(0));
    }
    expect_matches(check, std::string(cpu ? "CPU twin" : "device") + " smooth coat over Lambertian");
}

// Smooth absorbing slab in air: R and T are two delta lobes; every other bin must stay exactly empty.
void smooth_slab(bool cpu) {
    const glm::vec3 tau(0.0f, 0.2f, 2.0f);
    Stack s = make_stack("slab", {dielectric(1.5f, 0.0f, tau), dielectric(1.0f)});
    SimOptions o;
    o.theta_i_deg = {0.5, 45.5, 80.5};
    o.paths = cpu ? 1000000 : 4000000;
    o.seed = 5;
    SimResult r = run(s, o, cpu);
    BinGrid g(r);
    BinCheck check;
    for (size_t a = 0; a < r.angles.size(); ++a) {
        double ci = std::cos(o.theta_i_deg[a] * M_PI / 180);
        uint32_t mt = g.theta_bin(o.theta_i_deg[a]), mp = g.phi_bin(180.0);
        for (int side = 0; side < 2; ++side) {
            Slice sl = make_slice(r, a, Side(side));
            for (int c = 0; c < 3; ++c) {
                exact::RT rt = exact::smooth_slab(ci, 1.0, 1.5, tau[c]);
                double ex = side == 0 ? rt.R : rt.T;
                size_t b = size_t(mt) * g.n_phi + mp;
                double omega = g.projected_solid_angle(mt);
                check_value(check, sl.sum[b][c], sl.se[b][c] * omega, ex, "slab " + std::string(side ? "T" : "R"));
            }
            for (size_t b = 0; b < sl.sum.size(); ++b) {
                if (b != size_t(mt) * g.n_phi + mp) {
                    ASSERT_EQ(sl.sum[b], glm::dvec3(0)) << "energy outside the delta lobe";
                }
            }
        }
    }
    expect_matches(check, std::string(cpu ? "CPU twin" : "device") + " smooth absorbing slab");
}

// Smooth absorbing coat over a smooth conductor: R is one delta lobe.
void smooth_coat_conductor(bool cpu) {
    const glm::vec3 tau(0.1f, 0.5f, 0.0f), nc(0.27f, 0.68f, 1.22f), kc(3.6f, 2.6f, 2.3f);
    Stack s = make_stack("coat-conductor", {dielectric(1.5f, 0.0f, tau), conductor(nc, kc)});
    SimOptions o;
    o.theta_i_deg = {0.5, 40.5, 75.5};
    o.paths = cpu ? 1000000 : 4000000;
    o.seed = 9;
    SimResult r = run(s, o, cpu);
    BinGrid g(r);
    BinCheck check;
    for (size_t a = 0; a < r.angles.size(); ++a) {
        double ci = std::cos(o.theta_i_deg[a] * M_PI / 180);
        uint32_t mt = g.theta_bin(o.theta_i_deg[a]), mp = g.phi_bin(180.0);
        Slice sl = make_slice(r, a, kReflection);
        size_t b = size_t(mt) * g.n_phi + mp;
        for (int c = 0; c < 3; ++c) {
            double ex = exact::smooth_coat_conductor(ci, 1.0, 1.5, tau[c], nc[c], kc[c]);
            check_value(check, sl.sum[b][c], sl.se[b][c] * g.projected_solid_angle(mt), ex, "coat-conductor R");
        }
        for (size_t k = 0; k < sl.sum.size(); ++k) {
            if (k != b) { ASSERT_EQ(sl.sum[k], glm::dvec3(0)); }
        }
    }
    expect_matches(check, std::string(cpu ? "CPU twin" : "device") + " smooth coat over smooth conductor");
}

// One rough interface: a single scattering event, so the bins must equal the Walter et al. 2007 BSDF
// (GGX, height-correlated Smith), integrated over each bin by quadrature. This proves the rough event's
// sampling weight G2/G1, not only its directions. Dielectric (R and T, with the substrate's index below)
// and conductor (R).
void rough_interface(bool cpu, bool conductor_base) {
    const double alpha = 0.3, n = 1.5;
    const glm::vec3 nc(0.27f, 0.68f, 1.22f), kc(3.6f, 2.6f, 2.3f);
    Stack s = conductor_base ? make_stack("rough-conductor", {conductor(nc, kc, float(alpha))})
                             : make_stack("rough-dielectric", {dielectric(float(n), float(alpha))});
    SimOptions o;
    o.theta_i_deg = {20.5, 65.5};
    o.paths = cpu ? 3000000 : 8000000;
    o.dtheta_deg = 3;
    o.dphi_deg = 6;
    o.seed = 21;
    SimResult r = run(s, o, cpu);
    BinGrid g(r);
    BinCheck check;
    for (size_t a = 0; a < r.angles.size(); ++a) {
        double ti = o.theta_i_deg[a] * M_PI / 180;
        exact::V3 wi{std::sin(ti), 0, std::cos(ti)};
        for (int side = 0; side < (conductor_base ? 1 : 2); ++side) {
            Slice sl = make_slice(r, a, Side(side));
            const int K = 8;   // K x K quadrature of f cos over the bin
            auto exact_bin = [&](uint32_t t, uint32_t p, int c) {
                double acc = 0;
                for (int u = 0; u < K; ++u)
                    for (int v = 0; v < K; ++v) {
                        double th = (g.theta_lo(t) + (u + 0.5) / K * g.dtheta_deg) * M_PI / 180;
                        double ph = (g.phi_lo(p) + (v + 0.5) / K * g.dphi_deg) * M_PI / 180;
                        double z = side ? -std::cos(th) : std::cos(th);
                        exact::V3 wo{std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), z};
                        double f = side ? exact::rough_transmission(wi, wo, alpha, 1.0, n)
                                        : (conductor_base ? exact::rough_reflection(wi, wo, alpha, 1.0,
                                                                                    std::complex<double>(nc[c], kc[c]))
                                                          : exact::rough_reflection(wi, wo, alpha, 1.0, n));
                        acc += f * std::cos(th) * std::sin(th);
                    }
                return acc * (g.dtheta_deg * M_PI / 180 / K) * (g.dphi_deg * M_PI / 180 / K) /
                       g.projected_solid_angle(t);
            };
            compare_bins(check, sl, g, o.paths, conductor_base ? 3 : 1, exact_bin,
                         "theta_i " + std::to_string(o.theta_i_deg[a]) + " side " + std::to_string(side));
        }
    }
    expect_matches(
        check, std::string(cpu ? "CPU twin" : "device") + (conductor_base ? " rough conductor" : " rough dielectric"));
}

class ClosedForm : public GpuTest {};

TEST_F(ClosedForm, RoughDielectricInterfaceDevice) { rough_interface(false, false); }
TEST_F(ClosedForm, RoughDielectricInterfaceCpuTwin) { rough_interface(true, false); }
TEST_F(ClosedForm, RoughConductorDevice) { rough_interface(false, true); }

TEST_F(ClosedForm, SmoothCoatOverLambertianDevice) { coat_over_lambertian(false); }
TEST_F(ClosedForm, SmoothCoatOverLambertianCpuTwin) { coat_over_lambertian(true); }
TEST_F(ClosedForm, SmoothAbsorbingSlabDevice) { smooth_slab(false); }
TEST_F(ClosedForm, SmoothAbsorbingSlabCpuTwin) { smooth_slab(true); }
TEST_F(ClosedForm, SmoothCoatOverSmoothConductorDevice) { smooth_coat_conductor(false); }
TEST_F(ClosedForm, SmoothCoatOverSmoothConductorCpuTwin) { smooth_coat_conductor(true); }

// The exact formulas themselves, on textbook values.
TEST(Exact, FresnelTextbookValues) {
    EXPECT_NEAR(exact::fresnel(1.0, 1.0, 1.5), 0.04, 1e-12);
    EXPECT_NEAR(exact::fresnel(0.5, 1.0, 1.5), 0.08919, 1e-5);
    EXPECT_NEAR(exact::fresnel(1.0, std::complex<double>(1.0), std::complex<double>(0.2, 3.0)),
                (0.8 * 0.8 + 9) / (1.2 * 1.2 + 9), 1e-12);
    EXPECT_EQ(exact::fresnel(0.3, 1.5, 1.0), 1.0);   // beyond the critical angle
    // lossless slab conserves energy
    auto rt = exact::smooth_slab(0.6, 1.0, 1.5, 0.0);
    EXPECT_NEAR(rt.R + rt.T, 1.0, 1e-12);
    // white Lambertian under a clear coat reflects everything: F + int f_d cos = 1
    exact::CoatLambert cl(1.0, 1.5, 0.0, 1.0);
    double acc = 0;
    const int K = 20000;
    for (int k = 0; k < K; ++k) {
        double th = (k + 0.5) * (M_PI / 2) / K;
        acc += cl.diffuse(0.8, std::cos(th)) * std::cos(th) * std::sin(th);
    }
    EXPECT_NEAR(cl.specular(0.8) + acc * (M_PI / 2) / K * 2 * M_PI, 1.0, 1e-4);
}

}   // namespace
