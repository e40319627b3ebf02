// Blender Cycles' Principled coat and adobe/openpbr-bsdf's OpenPBR as their codes compute them, transcribed again here
// in double from the codes (blender/cycles v5.0.0 src/kernel/svm/closure.h, closure/bsdf_microfacet.h, bsdf_util.h;
// adobe/openpbr-bsdf @a29da969 impl/openpbr_bsdf.h, openpbr_coating_lobe.h, openpbr_diffuse_lobe.h,
// openpbr_microfacet_multiple_scattering_lobes.h, openpbr_lobe_utils.h) and held to the models' CPU twins direction by
// direction; the energy tables both read are the per-stack sets (host/models/stack_tables.cpp: recomputed at their
// nodes and checked against the published tables in tests/test_production_tables.cpp), read here as their lookups read
// them. Then their limits (an index-matched clear coat: Cycles' base alone), and their refusals.
#include "model_twin_on_stack.h"
#include "exact.h"
#include "gpu_fixture.h"
#include "model_twin.h"
#include "model_quadrature.h"
#include "models.h"

#include <array>
#include <complex>

using namespace gonio;
using namespace gonio_test;

namespace {

size_t model_index(const std::string& id) {
    for (size_t i = 0; i < model_registry().size(); ++i)
        if (model_registry()[i].id == id) return i;
    throw std::runtime_error("no model " + id);
}

// The directions of the check: l at theta_i = 0, 35, 70, 85 degrees in the x-z plane, v at theta_o = 10, 40, 75
// degrees and azimuths 0, 60, 180 degrees
struct Direction {
    exact::V3 l, v;
};
std::vector<Direction> directions() {
    std::vector<Direction> out;
    for (double ti : {0.0, 35.0, 70.0, 85.0})
        for (double to : {10.0, 40.0, 75.0})
            for (double phi : {0.0, 60.0, 180.0}) {
                const double a = ti * M_PI / 180, b = to * M_PI / 180, p = phi * M_PI / 180;
                out.push_back({{std::sin(a), 0, std::cos(a)},
                               {std::sin(b) * std::cos(p), std::sin(b) * std::sin(p), std::cos(b)}});
            }
    return out;
}

// A set of `nodes` values at mu = i / (nodes - 1) read at mu by linear interpolation (the lookups' reading along mu)
double along_mu(const std::vector<float>& t, uint32_t offset, uint32_t nodes, double mu) {
    const double x = std::clamp(mu, 0.0, 1.0) * (nodes - 1);
    const uint32_t i = std::min(uint32_t(x), nodes - 2);
    return t[offset + i] + (t[offset + i + 1] - t[offset + i]) * (x - i);
}

double schlick(double f0, double mu) { return f0 + (1 - f0) * std::pow(1 - mu, 5); }
// F82-tint as Cycles' fresnel_f82 and Adobe's openpbr_f82_tint write it: saturate(F0 + (1 - F0)(1 - mu)^5 - b mu
// (1 - mu)^6), b = (F0 + (1 - F0)(6/7)^5) (1 - tint) / ((1/7) (6/7)^6)
double f82_b(double f0, double tint) { return schlick(f0, 1.0 / 7) * (1 - tint) / (std::pow(6.0 / 7, 6) / 7); }
double f82(double f0, double b, double mu) {
    return std::clamp(schlick(f0, mu) - b * mu * std::pow(1 - mu, 6), 0.0, 1.0);
}
// the conductor base as the models' metal: F0 and the F82 tint from its n and k (docs/MODELS.md's mapping)
struct Metal {
    double f0, tint;
};
Metal metal_of(double n, double k) {
    const double f0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    return {f0, std::min(1.0, exact::fresnel(1.0 / 7, 1.0, std::complex<double>(n, k)) / schlick(f0, 1.0 / 7))};
}

const glm::vec3 kAlbedo(0.9f, 0.5f, 0.2f), kCuN(0.27f, 0.68f, 1.22f), kCuK(3.6f, 2.6f, 2.3f), kTint(0.1f, 0.3f, 0.6f);

// Cycles' Principled BSDF at Coat Weight 1 (closure.h): f = K_c f_coat + L_c tau_c f_base, with
//   K_c = 1 + F_ms (1 - E) / E (microfacet_ggx_preserve_energy), E = ggx_E(r_c, mu_v), F_ms = F_ss E_avg / (1 - F_ss
//   (1 - E_avg)), F_ss = (eta - 1) / (4.08567 + 1.00071 eta);
//   L_c = saturate(1 - (E + F_ms (1 - E)) (F0 + (1 - F0) s(r_c, mu_v, z_c))) (closure_layering_weight of the albedo
//   bsdf_albedo estimates, its closure weight carrying the darkening E + F_ms (1 - E));
//   tau_c = tint^(1 / mu_v^t), tint = exp(-2 tau);
//   a Lambertian Base Color / pi, or the metal's F82-tint GGX lobe with its own K from F_ss = F0 + (1 - F0) / 21 - b / 126;
// Blender 4.4 (+4.4): K_c = 1, L_c = 1 - F(mu_v).
TEST(ProductionModels, CyclesPrincipledIsItsClosureCode) {
    using exact::V3;
    int checked = 0;
    for (const std::string id : {"cycles-principled", "cycles-principled+4.4"})
        for (double eta : {1.5, 1.8})
            for (float ac : {0.02f, 0.2f, 0.6f})
                for (int base = 0; base < 3; ++base)   // Lambertian, copper alpha 0.3, smooth copper
                    for (int absorbs = 0; absorbs < 2; ++absorbs) {
                        const float ab = base == 1 ? 0.3f : 0.0f;
                        const glm::vec3 tau = absorbs ? kTint : glm::vec3(0.0f);
                        const Stack s =
                            make_stack("cycles", {dielectric(float(eta), ac, tau),
                                                  base == 0 ? lambertian(kAlbedo) : conductor(kCuN, kCuK, ab)});
                        const size_t m = model_index(id);
                        ASSERT_EQ(model_cannot_represent(m, s), "");
                        const bool v44 = id == "cycles-principled+4.4";
                        const std::vector<float> t = stack_tables(pack_stack(s), STACK_TABLES_CYCLES_ENERGY);
                        const double fss = (eta - 1) / (4.08567 + 1.00071 * eta);
                        const double f0c = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
                        for (const Direction& d : directions()) {
                            const V3 l = d.l, v = d.v;
                            const double mu_v = v.z;
                            const glm::dvec3 got = model_value_cpu(m, s, glm::vec3(float(l.x), 0.0f, float(l.z)),
                                                                   glm::vec3(float(v.x), float(v.y), float(v.z)));
                            const double e = along_mu(t, STACK_TABLE_CYCLES_COAT_E, CYCLES_E_NODES, mu_v);
                            const double e_avg = t[STACK_TABLE_CYCLES_COAT_E + CYCLES_E_NODES];
                            const double fms = fss * e_avg / (1 - fss * (1 - e_avg));
                            const double k_c = v44 ? 1.0 : 1 + fms * (1 - e) / e;
                            const double sv = along_mu(t, STACK_TABLE_CYCLES_COAT_S, CYCLES_S_NODES, mu_v);
                            const double albedo =
                                v44 ? exact::fresnel(mu_v, 1.0, eta) : (e + fms * (1 - e)) * (f0c + (1 - f0c) * sv);
                            const double layering = std::clamp(1 - albedo, 0.0, 1.0);
                            const double mu_t = std::sqrt(1 - (1 - mu_v * mu_v) / (eta * eta));
                            const double coat = k_c * exact::rough_reflection(l, v, ac, 1.0, eta);
                            for (int c = 0; c < 3; ++c) {
                                double f_base = kAlbedo[c] / M_PI;
                                if (base > 0) {
                                    const Metal mt = metal_of(kCuN[c], kCuK[c]);
                                    const double b = f82_b(mt.f0, mt.tint);
                                    const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                                    const double em = along_mu(t, STACK_TABLE_CYCLES_BASE_E, CYCLES_E_NODES, mu_v);
                                    const double em_avg = t[STACK_TABLE_CYCLES_BASE_E + CYCLES_E_NODES];
                                    const double fss_m = mt.f0 + (1 - mt.f0) / 21 - b / 126;
                                    const double fms_m = fss_m * em_avg / (1 - fss_m * (1 - em_avg));
                                    f_base = f82(mt.f0, b, exact::dot(v, h)) *
                                             exact::ggx_lobe(l, v, std::max(ab, 1e-4f)) * (1 + fms_m * (1 - em) / em);
                                }
                                const double want = coat + layering * std::exp(-2 * tau[c] / mu_t) * f_base;
                                EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                                    << id << " eta " << eta << " alpha " << ac << " base " << base << " absorbs "
                                    << absorbs << " l " << l.x << "," << l.z << " v " << v.x << "," << v.y << "," << v.z
                                    << " channel " << c;
                            }
                            ++checked;
                        }
                    }
    EXPECT_EQ(checked, 2 * 2 * 3 * 3 * 2 * 36);
}

// An index-matched clear coat (Coat IOR 1 relative to the exterior) removes Cycles' coat: F = 0, the estimate reflects
// nothing (its table is read above IOR 1 only), no tint: f is the base alone, Base Color / pi
TEST(ProductionModels, CyclesIndexMatchedCoatLeavesTheBase) {
    const Stack s = make_stack("matched", {dielectric(1.0f, 0.2f), lambertian(kAlbedo)});
    for (const std::string id : {"cycles-principled", "cycles-principled+4.4"}) {
        const size_t m = model_index(id);
        for (const Direction& d : directions()) {
            const glm::dvec3 got = model_value_cpu(m, s, glm::vec3(float(d.l.x), 0.0f, float(d.l.z)),
                                                   glm::vec3(float(d.v.x), float(d.v.y), float(d.v.z)));
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], kAlbedo[c] / M_PI, 1e-6) << id;
        }
    }
}

// adobe/openpbr-bsdf's openpbr_eval / mu_l at coat_weight 1 (OPENPBR_RECIPROCAL_COAT_AND_FUZZ 0, and 1 for +reciprocal):
//   f = f_coat + Delta T(mu_v) T(mu_l) (1 - E_c(mu_v)) [(1 - E_c(mu_l))] f_base
// f_coat with separable G and exact Fresnel at |v.h|; E_c = 1 - OD(eta_c, alpha_c, mu) (F(mu) for a smooth coat);
// T = exp(-tau / mu^t); r' = (min(1, r^4 + (1 - 1/eta_c) r_c^4))^(1/4); K = mix(avgF(eta_c), 1 - (1 - avgF(eta_c)) /
// eta_c^2, rough_b), Delta = (1 - K) / (1 - E_b K), avgF Kulla & Conty's fit; a Lambertian (specular_weight 0, r = 0):
// s0 = avgF(1), rough_b = mix(1, r', s0), E_b = mix(A, 1, s0), f_base = A / pi (1 + 1e-7 A) OD1(mu_v) OD1(mu_l) / ODA1;
// a metal (r = sqrt(alpha_base)): rough_b = r', E_b = avgF82 = saturate(F0 + (1 - F0) / 21 - b / 126), f_base =
// F82(|v.h|) D G1 G1 / (4 mu_l mu_v) at alpha'_s = r'^2 plus avgF82^2 min(IM(mu_v) IM(mu_l) / IMA, 1 / mu_l) / pi where
// r' >= 0.04.
TEST(ProductionModels, OpenpbrAdobeIsItsCode) {
    using exact::V3;
    auto avg_f = [](double e) {
        return e > 1 ? (e - 1) / (4.08567 + 1.00071 * e)
                     : 0.997118 + 0.1014 * e - 0.965241 * e * e - 0.130607 * e * e * e;
    };
    auto separable_lobe = [](V3 l, V3 v, double a) {
        const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
        return exact::ggx_D(h, a) * exact::G2_separable(l, v, a) / (4 * l.z * v.z);
    };
    int checked = 0;
    for (const std::string id : {"openpbr-adobe", "openpbr-adobe+reciprocal"})
        for (double eta : {1.5, 1.6, 2.8})
            for (float ac : {0.0f, 0.2f, 0.6f})
                for (int base = 0; base < 3; ++base)   // Lambertian, copper alpha 0.3, smooth copper
                    for (int absorbs = 0; absorbs < 2; ++absorbs) {
                        const float ab = base == 1 ? 0.3f : 0.0f;
                        const glm::vec3 tau = absorbs ? kTint : glm::vec3(0.0f);
                        const Stack s =
                            make_stack("adobe", {dielectric(float(eta), ac, tau),
                                                 base == 0 ? lambertian(kAlbedo) : conductor(kCuN, kCuK, ab)});
                        const size_t m = model_index(id);
                        ASSERT_EQ(model_cannot_represent(m, s), "");
                        const bool reciprocal = id == "openpbr-adobe+reciprocal";
                        const std::vector<float> t = stack_tables(pack_stack(s), STACK_TABLES_ADOBE_ENERGY);
                        auto e_c = [&](double mu) {
                            return ac == 0.0f ? exact::fresnel(mu, 1.0, eta)
                                              : along_mu(t, STACK_TABLE_ADOBE_COAT, ADOBE_TABLE_NODES, mu);
                        };
                        auto tint = [&](double mu, int c) {
                            return std::exp(-tau[c] / std::sqrt(1 - (1 - mu * mu) / (eta * eta)));
                        };
                        const double r = base == 0 ? 0.0 : std::sqrt(double(ab)), rc = std::sqrt(double(ac));
                        const double rp =
                            std::pow(std::min(1.0, std::pow(r, 4) + (1 - 1 / eta) * std::pow(rc, 4)), 0.25);
                        const double k_s = avg_f(eta), k_r = 1 - (1 - k_s) / (eta * eta);
                        for (const Direction& d : directions()) {
                            const V3 l = d.l, v = d.v;
                            const glm::dvec3 got = model_value_cpu(m, s, glm::vec3(float(l.x), 0.0f, float(l.z)),
                                                                   glm::vec3(float(v.x), float(v.y), float(v.z)));
                            const V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
                            const double coat = exact::fresnel(std::fabs(exact::dot(v, h)), 1.0, eta) *
                                                exact::ggx_D(h, std::max(ac, 1e-4f)) *
                                                exact::G2_separable(l, v, std::max(ac, 1e-4f)) / (4 * l.z * v.z);
                            const double scale = (1 - e_c(v.z)) * (reciprocal ? 1 - e_c(l.z) : 1.0);
                            for (int c = 0; c < 3; ++c) {
                                double f_base, e_b, rough_b;
                                if (base == 0) {
                                    const double s0 = avg_f(1.0), a = kAlbedo[c];
                                    rough_b = 1 + (rp - 1) * s0;
                                    e_b = a + (1 - a) * s0;
                                    f_base = a / M_PI * (1 + 1e-7 * a) *
                                             along_mu(t, STACK_TABLE_ADOBE_DIFFUSE, ADOBE_TABLE_NODES, v.z) *
                                             along_mu(t, STACK_TABLE_ADOBE_DIFFUSE, ADOBE_TABLE_NODES, l.z) /
                                             t[STACK_TABLE_ADOBE_DIFFUSE + ADOBE_TABLE_NODES];
                                } else {
                                    const Metal mt = metal_of(kCuN[c], kCuK[c]);
                                    const double b = f82_b(mt.f0, mt.tint);
                                    const double f_avg = std::clamp(mt.f0 + (1 - mt.f0) / 21 - b / 126, 0.0, 1.0);
                                    rough_b = rp;
                                    e_b = f_avg;
                                    f_base = f82(mt.f0, b, std::fabs(exact::dot(v, h))) *
                                             separable_lobe(l, v, std::max(rp * rp, 1e-4));
                                    if (rp >= 0.04) {
                                        const double im = along_mu(t, STACK_TABLE_ADOBE_METAL, ADOBE_TABLE_NODES, v.z) *
                                                          along_mu(t, STACK_TABLE_ADOBE_METAL, ADOBE_TABLE_NODES, l.z) /
                                                          t[STACK_TABLE_ADOBE_METAL + ADOBE_TABLE_NODES];
                                        f_base += f_avg * f_avg * std::min(im, 1 / l.z) / M_PI;
                                    }
                                }
                                const double k = k_s + (k_r - k_s) * rough_b;
                                const double delta = (1 - k) / (1 - e_b * k);
                                const double want = coat + delta * tint(v.z, c) * tint(l.z, c) * scale * f_base;
                                EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                                    << id << " eta " << eta << " alpha " << ac << " base " << base << " absorbs "
                                    << absorbs << " l " << l.x << "," << l.z << " v " << v.x << "," << v.y << "," << v.z
                                    << " channel " << c;
                            }
                            ++checked;
                        }
                    }
    EXPECT_EQ(checked, 2 * 3 * 3 * 3 * 2 * 36);
}

// The interfaced Lambertian microfacets (Meneveaux et al. 2018, as Nanairo @23fb6dee computes them): the flat
// interface's r_e against Nanairo's closed form (calcRe, layered_diffuse.cpp), and the model against the integral it
// stands for, computed here by another quadrature (below), the body
//   k_d / (pi eta^2 (1 - k_d r_i)) int (1 - F(l.m)) (1 - F(v.m)) (l.m)+ (v.m)+ / (mu_l mu_v) D G1(l) G1(v) dm
// plus Walter's lobe with separable G; at the table's nodes the model's table is its own quadrature (64 x 32 visible
// normals), between them its trilinear reading (the backscatter direction, l = v at 60 degrees, is Nanairo's
// one-sample estimator's 0.20674 +- 0.00004 at k_d 0.8, alpha 0.3 over 4e6 samples: the model gives 0.20670); measured
// within 2.1e-3 (alpha 0.8, between the nodes), 8e-4 at the nodes, held to 3e-3
TEST(ProductionModels, InterfacedLambertianIsItsIntegral) {
    using exact::V3;
    // Nanairo's closed form of r_e (n > 1), and r_i = 1 - (1 - r_e) / n^2
    auto r_e = [](double n) {
        const double n2 = n * n, n4 = n2 * n2, a = n + 1, b = n - 1, c = n2 + 1, d = n2 - 1, e = n4 - 1;
        const double t1 = 2 * n * n2 * e * (a * a - 2), t2 = std::pow(c * b, 3) * (3 * n + 1) / 6;
        const double t3 = 8 * n4 * (n4 + 1) * std::log(n), t4 = n2 * std::pow(d, 4) * std::log(b / a);
        return 0.5 + (-t1 + t2 + t3 + t4) / (c * e * e);
    };
    for (double n : {1.1, 1.33, 1.5, 2.0})
        EXPECT_NEAR(interfaced_internal_reflectance(float(n)), 1 - (1 - r_e(n)) / (n * n), 2e-6) << n;
    const size_t m = model_index("interfaced-lambertian");
    const glm::vec3 kd(0.8f, 0.5f, 1.0f);
    // the body's integral as the mean over the visible normals of v (Heitz 2018's stretched hemisphere, in double,
    // 1024 x 1024 midpoint nodes of its square) of (1 - F(l.m)) (1 - F(v.m)) (l.m)+ G1(l) / mu_l: the same integral
    // as over D with G1(l) G1(v) (l.m)+ (v.m)+ / (mu_l mu_v), taken from v's side where the model's table takes it
    // from the more grazing one's, by another map and rule
    auto body_integral = [](V3 l, V3 v, double eta, double alpha) {
        const V3 vh = exact::norm({alpha * v.x, alpha * v.y, v.z});
        const double len2 = vh.x * vh.x + vh.y * vh.y;
        const V3 t1 = len2 > 0 ? V3{-vh.y / std::sqrt(len2), vh.x / std::sqrt(len2), 0} : V3{1, 0, 0};
        const V3 t2{vh.y * t1.z - vh.z * t1.y, vh.z * t1.x - vh.x * t1.z, vh.x * t1.y - vh.y * t1.x};
        const int n = 1024;
        double sum = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const double r = std::sqrt((i + 0.5) / n), ph = 2 * M_PI * (j + 0.5) / n;
                const double a1 = r * std::cos(ph), s = 0.5 * (1 + vh.z);
                const double a2 = (1 - s) * std::sqrt(1 - a1 * a1) + s * r * std::sin(ph);
                const double a3 = std::sqrt(std::max(0.0, 1 - a1 * a1 - a2 * a2));
                const V3 nh{a1 * t1.x + a2 * t2.x + a3 * vh.x, a1 * t1.y + a2 * t2.y + a3 * vh.y,
                            a1 * t1.z + a2 * t2.z + a3 * vh.z};
                const V3 mm = exact::norm({alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)});
                const double lm = exact::dot(l, mm), vm = exact::dot(v, mm);
                if (lm <= 0) continue;
                sum += (1 - exact::fresnel(lm, 1.0, eta)) * (1 - exact::fresnel(vm, 1.0, eta)) * lm *
                       exact::ggx_G1_walter(l, alpha) / l.z;
            }
        return sum / (double(n) * n);
    };
    double worst = 0;
    for (double eta : {1.5, 1.33})
        for (float alpha : {0.05f, 0.3f, 0.8f}) {
            const Stack s = make_stack("interfaced", {dielectric(float(eta), alpha), lambertian(kd)});
            ASSERT_EQ(model_cannot_represent(m, s), "");
            const double r_i = 1 - (1 - r_e(eta)) / (eta * eta);
            for (const Direction& d :
                 {Direction{{0, 0, 1}, {0, 0, 1}},
                  Direction{{std::sqrt(0.5), 0, std::sqrt(0.5)}, {-std::sqrt(0.5), 0, std::sqrt(0.5)}},
                  Direction{{std::sqrt(0.75), 0, 0.5}, {std::sqrt(0.75), 0, 0.5}},
                  Direction{{std::sin(1.2217), 0, std::cos(1.2217)}, {0, 0.5, std::sqrt(0.75)}},
                  Direction{{std::sin(0.3), 0, std::cos(0.3)}, {0.6, 0.2, std::sqrt(0.6)}}}) {
                const glm::dvec3 got = model_value_cpu(m, s, glm::vec3(float(d.l.x), float(d.l.y), float(d.l.z)),
                                                       glm::vec3(float(d.v.x), float(d.v.y), float(d.v.z)));
                const V3 h = exact::norm({d.l.x + d.v.x, d.l.y + d.v.y, d.l.z + d.v.z});
                const double spec = exact::fresnel(exact::dot(d.l, h), 1.0, eta) * exact::ggx_D(h, alpha) *
                                    exact::G2_separable(d.l, d.v, alpha) / (4 * d.l.z * d.v.z);
                const double b = body_integral(d.l, d.v, eta, alpha);
                for (int c = 0; c < 3; ++c) {
                    const double want = spec + kd[c] / (M_PI * eta * eta * (1 - kd[c] * r_i)) * b;
                    worst = std::max(worst, std::fabs(got[c] - want) / want);
                    EXPECT_NEAR(got[c], want, 3e-3 * want)
                        << "eta " << eta << " alpha " << alpha << " l " << d.l.x << "," << d.l.z << " v " << d.v.x
                        << "," << d.v.y << "," << d.v.z << " channel " << c;
                }
            }
        }
    std::printf("interfaced-lambertian against its integral: largest relative departure %.2e\n", worst);
    // and against Nanairo's own one-sample estimator of the body, run independently of this code: 0.20674 +- 0.00004
    // at l = v at 60 degrees, k_d 0.8, alpha 0.3, eta 1.5 (4e6 samples); the model less its specular lobe within
    // three of that standard error
    const Stack s = make_stack("interfaced", {dielectric(1.5f, 0.3f), lambertian(kd)});
    const V3 b{std::sqrt(0.75), 0, 0.5};
    const double spec =
        exact::fresnel(1.0, 1.0, 1.5) * exact::ggx_D(b, 0.3) * exact::G2_separable(b, b, 0.3) / (4 * b.z * b.z);
    const glm::vec3 back(float(b.x), 0.0f, float(b.z));
    const double body = model_value_cpu(m, s, back, back).x - spec;
    std::printf("interfaced-lambertian's body at l = v = 60 degrees: %.5f (Nanairo's estimator 0.20674 +- 0.00004)\n",
                body);
    EXPECT_NEAR(body, 0.20674, 3 * 0.00004);
}

// Its limits: a smooth interface (alpha 1e-4) is the flat interfaced Lambertian, k_d (1 - F(mu_l)) (1 - F(mu_v)) /
// (pi eta^2 (1 - k_d r_i)) off the mirror direction, whose albedo at k_d = 1 is 1 (Simonot 2009's energy balance)
TEST(ProductionModels, InterfacedLambertianLimits) {
    const size_t m = model_index("interfaced-lambertian");
    const double eta = 1.5, r_i = interfaced_internal_reflectance(1.5f);
    const Stack s = make_stack("smooth", {dielectric(1.5f, 0.0f), lambertian(glm::vec3(0.8f, 0.3f, 1.0f))});
    const ModelCpu body(m, pack_stack(s));   // the body term (the specular delta, GGX of alpha 1e-4 here, left out)
    for (const Direction& d : directions()) {
        const glm::dvec3 got = body.value(glm::vec3(float(d.l.x), 0.0f, float(d.l.z)),
                                          glm::vec3(float(d.v.x), float(d.v.y), float(d.v.z)), kModelTermBase);
        for (int c = 0; c < 3; ++c) {
            const double kd = std::array<double, 3>{0.8, 0.3, 1.0}[c];
            const double want = kd * (1 - exact::fresnel(d.l.z, 1.0, eta)) * (1 - exact::fresnel(d.v.z, 1.0, eta)) /
                                (M_PI * eta * eta * (1 - kd * r_i));
            EXPECT_NEAR(got[c], want, 1e-4 * want) << d.l.z << " " << d.v.z << " channel " << c;
        }
    }
    // the white furnace: over a white body the flat interface's F(mu_l) (its delta) and the body's albedo sum to 1;
    // rough microfacets (single scattering, masked) return less, never more
    const Stack white = make_stack("white", {dielectric(1.5f, 0.0f), lambertian(glm::vec3(1.0f))});
    const ModelCpu smooth(m, pack_stack(white));
    for (double t : {0.0, 40.0, 75.0}) {
        const glm::vec3 l(float(std::sin(t * M_PI / 180)), 0.0f, float(std::cos(t * M_PI / 180)));
        const glm::dvec3 e = hemisphere_integral([&](glm::vec3 v) { return smooth.value(l, v, kModelTermBase); }, 600);
        const double total = e.x + exact::fresnel(std::cos(t * M_PI / 180), 1.0, eta);
        std::printf("interfaced-lambertian, smooth interface over white: albedo at %g degrees %.5f\n", t, total);
        EXPECT_NEAR(total, 1.0, 2e-3) << t;
    }
    // (and at IOR 1, Lambertian microfacets, to the horizon, where the float Fresnel of an index-matched interface is 1
    // below mu 2.4e-4: at 89.9 degrees 1.72 before the flat part was taken at 1e-3 or above)
    for (const auto& [n, alpha] : {std::pair{1.5f, 0.3f}, std::pair{1.5f, 1.0f}, std::pair{1.0f, 0.3f}}) {
        const Stack rough = make_stack("rough-white", {dielectric(n, alpha), lambertian(glm::vec3(1.0f))});
        for (double t : {0.0, 60.0, 85.0, 89.9}) {
            const glm::dvec3 e = albedo_by_quadrature(m, rough, t, alpha, false, 600, 180);
            std::printf("interfaced-lambertian, IOR %g, alpha %g over white: albedo at %g degrees %.4f\n", n, alpha, t,
                        e.x);
            EXPECT_LT(e.x, 1.0 + 1e-3) << alpha << " " << t;
            EXPECT_GT(e.x, 0.4) << alpha << " " << t;
        }
    }
}

// A dielectric base under the coat (three layers: the coat, a dielectric interface of IOR n_b, a Lambertian of albedo
// A), as each definition that takes it computes it, transcribed again in double:
//   openpbr (OpenPBR v1.1.1 "Dielectric base", "Glossy-diffuse", "Coat"): f_coat + T (1 - E_c(v)) Delta [f_spec +
//     (1 - E_s(v)) A / pi], f_spec the GGX reflection of eta_s = max(n_b, n_c) / min(n_b, n_c) (the TIR fix) at the
//     roughened alpha'_B with G2 times the energy compensation C(mu_v) = 1 + E_F(eta_s) (1 - E_ss(mu_v)) / E_ss(mu_v)
//     (E_F the exact Fresnel's cosine-weighted average)
//     ("Microfacet model"; E_ss the lobe's albedo at F = 1; +single: C = 1), E_s its directional albedo times C,
//     Delta = (1 - K) / (1 - E_b K), K = lerp(F(mu_v, eta_c), K_r, r_d), r_d = lerp(1, r_B, F_s),
//     F_s = ((1 - eta_s) / (1 + eta_s))^2, E_b = E_s(1) + (1 - E_s(1)) A;
//   gltf-clearcoat (Appendix B's fresnel_mix under KHR_materials_clearcoat): (1 - Fc(n.v)) [(1 - F(v.h)) A / pi +
//     F(v.h) D Vis(alpha_b)] + Fc D Vis(alpha_c), F Schlick of f0 ((n_b - 1) / (n_b + 1))^2;
//   standard-surface ("Specular" under "Coating"): f_coat + coat_color (1 - E_c(v)) [f_spec(n_b) + (1 - E_spec(v))
//     A / pi], the specular's IOR the base's relative to the exterior (+osl: 1 - F(n.v) for both reflectances).
// The albedos E_s, E_spec are the per-stack sets (checked here at three nodes against a hemisphere quadrature of
// their lobes); the coat's E_c is the coat-albedo set (checked in Models.OpenpbrIsTheSpecificationsFormula).
namespace {

// One case of a dielectric base under the coat: the model, the stack, its tables, and what the definitions derive
struct DielectricBaseCase {
    std::string id;
    float nb, ac, ab = 0.15f;   // the base's IOR, the coat's and the base's roughness
    glm::vec3 tau, A;   // the coat's optical depth, the Lambertian's albedo
    bool separable, gltf, openpbr;
    std::vector<float> t;   // the per-stack tables
    double eta = 1.5, eta_s, a_spec;   // openpbr: the TIR-fixed relative IOR, the roughened base roughness
    uint32_t e_set, coat_set, lobe_set;   // the base's and the coat's albedo sets, the base lobe's at F = 1
    bool compensated;   // openpbr's base lobe times 1 + F_avg (1 - E_ss(mu_v)) / E_ss(mu_v) (not +single)

    DielectricBaseCase(const std::string& model, float n_b, float a_c, glm::vec3 optical_depth, glm::vec3 albedo,
                       const Stack& s)
        : id(model), nb(n_b), ac(a_c), tau(optical_depth), A(albedo) {
        separable = id == "openpbr+separable";   // the separable G1(l) G1(v) in every lobe and in both albedos
        gltf = id.rfind("gltf", 0) == 0;
        openpbr = id.rfind("openpbr", 0) == 0;
        t = stack_tables(pack_stack(s), STACK_TABLES_COAT_ALBEDO | STACK_TABLES_OPENPBR_BASE_ALBEDO |
                                            STACK_TABLES_STANDARD_SURFACE_BASE_ALBEDO | STACK_TABLES_OPENPBR_SEPARABLE |
                                            STACK_TABLES_OPENPBR_LOBE_ALBEDO);
        compensated = openpbr && id != "openpbr+single";
        const double rel = nb / eta;
        eta_s = rel >= 1 ? rel : 1 / rel;
        a_spec = std::sqrt(std::min(1.0, double(ab) * ab + 2.0 * ac * ac));
        if (id == "openpbr+pr261") {
            const double B = 1.05 * (eta - 1) * std::sqrt(1 + eta * eta) / eta;
            a_spec = 0.85 * std::tanh(std::hypot(eta * ab, B * ac) / 0.85);
        }
        e_set = id == "openpbr+pr261" ? STACK_TABLE_OPENPBR_BASE_PR261
                : separable           ? STACK_TABLE_OPENPBR_SEPARABLE_BASE
                : openpbr             ? STACK_TABLE_OPENPBR_BASE
                                      : STACK_TABLE_STANDARD_SURFACE_BASE_ALBEDO;
        coat_set = separable ? STACK_TABLE_OPENPBR_SEPARABLE_COAT : STACK_TABLE_COAT_ALBEDO;
        lobe_set = id == "openpbr+pr261" ? STACK_TABLE_OPENPBR_LOBE_PR261
                   : separable           ? STACK_TABLE_OPENPBR_LOBE_SEPARABLE
                                         : STACK_TABLE_OPENPBR_LOBE;
    }
    // a dielectric's GGX reflection, F D G
    double lobe(exact::V3 l, exact::V3 v, double a, double n) const {
        if (!separable) return exact::rough_reflection(l, v, a, 1.0, n);
        const exact::V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
        return exact::fresnel(exact::dot(l, h), 1.0, n) * exact::ggx_D(h, a) * exact::G2_separable(l, v, a) /
               (4 * l.z * v.z);
    }
    // the same lobe with F = 1, D G
    double lobe_f1(exact::V3 l, exact::V3 v, double a) const {
        const exact::V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
        return exact::ggx_D(h, a) * (separable ? exact::G2_separable(l, v, a) : exact::G2(l, v, a)) / (4 * l.z * v.z);
    }
    double e_base(double mu) const { return along_mu(t, e_set, COAT_ALBEDO_NODES, mu); }
    double e_coat(double mu) const { return along_mu(t, coat_set, COAT_ALBEDO_NODES, mu); }
    // the compensation at mu, F_avg = E_F(eta_s) = 2 int F(mu, eta_s) mu dmu (4000-node midpoint rule); 1 where not
    // compensated
    double compensation(double mu) const {
        if (!compensated) return 1.0;
        double f_avg = 0;
        for (int j = 0; j < 4000; ++j)
            f_avg += 2 * exact::fresnel((j + 0.5) / 4000, 1.0, eta_s) * (j + 0.5) / 4000 / 4000;
        const double e = along_mu(t, lobe_set, COAT_ALBEDO_NODES, mu);
        return 1 + f_avg * (1 - e) / e;
    }
};

// OpenPBR v1.1.1's dielectric base under its coat (the test's header), channel c
double openpbr_dielectric_base(const DielectricBaseCase& k, exact::V3 l, exact::V3 v, int c) {
    const double eta = k.eta, eta_s = k.eta_s;
    const double f_spec = k.lobe(l, v, std::max(k.a_spec, 1e-4), eta_s) * k.compensation(v.z);
    const double f_diff = (1 - k.e_base(v.z) * k.compensation(v.z)) * k.A[c] / M_PI;
    const double e_s1 = k.e_base(1.0) * k.compensation(1.0), e_b = e_s1 + (1 - e_s1) * k.A[c];
    const double f_s = std::pow((1 - eta_s) / (1 + eta_s), 2);
    const double r_d = (1 - f_s) + f_s * std::sqrt(double(k.ab));
    const double k_r = 1 - (1 - exact::openpbr_fresnel_albedo(eta)) / (eta * eta);
    const double K = (1 - r_d) * exact::fresnel(v.z, 1.0, eta) + r_d * k_r;
    const double t2 = k.id == "openpbr+dev1.2" ? std::exp(-2.0 * k.tau[c]) : 1.0;
    const double delta = (1 - K) / (1 - e_b * t2 * K);
    const double T =
        std::exp(-k.tau[c] * (1 / exact::refracted_cosine(l.z, eta) + 1 / exact::refracted_cosine(v.z, eta)));
    return k.lobe(l, v, k.ac, eta) + T * (1 - k.e_coat(v.z)) * delta * (f_spec + f_diff);
}

// glTF's clearcoat over its metal-rough dielectric (Appendix B's fresnel_mix), and the Sample Viewer's reading
double gltf_dielectric_base(const DielectricBaseCase& k, exact::V3 l, exact::V3 v, int c) {
    auto gltf_lobe = [&](double a) {   // D Vis, Appendix B
        const exact::V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
        const double a2 = a * a, d = h.z * h.z * (a2 - 1) + 1;
        const double vis =
            1 / (2 * (v.z * std::sqrt(a2 + (1 - a2) * l.z * l.z) + l.z * std::sqrt(a2 + (1 - a2) * v.z * v.z)));
        return a2 / (M_PI * d * d) * vis;
    };
    const exact::V3 h = exact::norm({l.x + v.x, l.y + v.y, l.z + v.z});
    const double fc = schlick(0.04, v.z), f0 = std::pow((k.nb - 1.0) / (k.nb + 1.0), 2);
    const double fr = schlick(f0, std::fabs(exact::dot(v, h)));
    const double coat_w = k.id == "gltf-clearcoat+viewer" ? schlick(0.04, exact::dot(v, h)) : fc;
    return (1 - fc) * ((1 - fr) * k.A[c] / M_PI + fr * gltf_lobe(k.ab)) + coat_w * gltf_lobe(k.ac);
}

// Standard Surface's specular under its coating (+osl: 1 - F(n.v) for both reflectances)
double standard_surface_dielectric_base(const DielectricBaseCase& k, exact::V3 l, exact::V3 v, int c) {
    const bool osl = k.id == "standard-surface+osl";
    const double pass_c = osl ? 1 - exact::fresnel(v.z, 1.0, k.eta) : 1 - k.e_coat(v.z);
    const double pass_b = osl ? 1 - exact::fresnel(v.z, 1.0, k.nb) : 1 - k.e_base(v.z);
    return exact::rough_reflection(l, v, k.ac, 1.0, k.eta) +
           std::exp(-2.0 * k.tau[c]) * pass_c *
               (exact::rough_reflection(l, v, k.ab, 1.0, k.nb) + pass_b * k.A[c] / M_PI);
}

// The base's albedo set at three nodes against a hemisphere quadrature of its lobe; returns how many were checked
int check_base_albedo_set(const DielectricBaseCase& k) {
    const double e_eta = k.openpbr ? k.eta_s : k.nb, e_alpha = k.openpbr ? k.a_spec : k.ab;
    int checked = 0;
    for (uint32_t i : {16u, 40u, 64u}) {
        const double mu = coat_albedo_node_mu(i);
        const exact::V3 v{std::sqrt(1 - mu * mu), 0, mu};
        const double e = hemisphere_integral(
                             [&](glm::vec3 o) {
                                 return glm::dvec3(o.z > 0 ? k.lobe(v, {o.x, o.y, o.z}, e_alpha, e_eta) : 0.0);
                             },
                             400)
                             .x;
        EXPECT_NEAR(k.t[k.e_set + i], e, 2e-3) << k.id << " E at mu " << mu << ", n_b " << k.nb;
        ++checked;
        if (!k.compensated) continue;
        const double e_ss = hemisphere_integral(
                                [&](glm::vec3 o) {
                                    return glm::dvec3(o.z > 0 ? k.lobe_f1(v, {o.x, o.y, o.z}, e_alpha) : 0.0);
                                },
                                400)
                                .x;
        EXPECT_NEAR(k.t[k.lobe_set + i], e_ss, 2e-3) << k.id << " E_ss at mu " << mu << ", n_b " << k.nb;
    }
    return checked;
}

// The model against its definition at the test's 36 direction pairs
void check_dielectric_base(const DielectricBaseCase& k, size_t m, const Stack& s) {
    for (const Direction& d : directions()) {
        const exact::V3 l = d.l, v = d.v;
        const glm::dvec3 got = model_value_cpu(m, s, glm::vec3(float(l.x), 0.0f, float(l.z)),
                                               glm::vec3(float(v.x), float(v.y), float(v.z)));
        for (int c = 0; c < 3; ++c) {
            const double want = k.openpbr ? openpbr_dielectric_base(k, l, v, c)
                                : k.gltf  ? gltf_dielectric_base(k, l, v, c)
                                          : standard_surface_dielectric_base(k, l, v, c);
            EXPECT_NEAR(got[c], want, 5e-5 * want + 1e-7)
                << k.id << " n_b " << k.nb << " alpha_c " << k.ac << " tau " << k.tau.x << " l " << l.x << "," << l.z
                << " v " << v.x << "," << v.y << "," << v.z << " channel " << c;
        }
    }
}

// The white furnace OpenPBR's specification claims ("white dielectric" under a white coat) and Standard Surface's
// layering gives from the viewer: over a white diffuse, E_s(v) + (1 - E_s(v)) = 1 below the coat, E_b = 1 and
// Delta = 1, so all the light reaching v, integrated over l
void expect_white_dielectric_base_furnace() {
    const Stack white =
        make_stack("white", {dielectric(1.5f, 0.3f), dielectric(1.59f, 0.15f), lambertian(glm::vec3(1.0f))});
    for (const std::string id : {"openpbr", "standard-surface"})
        for (double to : {0.0, 40.0, 75.0}) {
            const glm::vec3 v(float(std::sin(to * M_PI / 180)), 0.0f, float(std::cos(to * M_PI / 180)));
            const glm::dvec3 e =
                hemisphere_integral([&](glm::vec3 l) { return model_value_cpu(model_index(id), white, l, v); }, 600);
            std::printf("%s, a white dielectric base under a clear coat: albedo seen from theta_o %g: %.5f\n",
                        id.c_str(), to, e.x);
            EXPECT_NEAR(e.x, 1.0, 3e-3) << id << " theta_o " << to;
        }
}

}   // namespace

TEST(ProductionModels, DielectricBaseIsEachDefinitionsFormula) {
    const glm::vec3 A(0.7f, 0.2f, 0.1f), tint(0.1f, 0.2f, 0.4f);
    int checked = 0, tables_checked = 0;
    for (const std::string id : {"openpbr", "openpbr+pr261", "openpbr+dev1.2", "openpbr+separable", "openpbr+single",
                                 "gltf-clearcoat", "gltf-clearcoat+viewer", "standard-surface", "standard-surface+osl"})
        for (float nb : {1.59f, 1.3f, 2.0f})
            for (float ac : {0.02f, 0.3f})
                for (int absorbs = 0; absorbs < 2; ++absorbs) {
                    const glm::vec3 tau = absorbs ? tint : glm::vec3(0.0f);
                    const Stack s = make_stack("dielectric-base",
                                               {dielectric(1.5f, ac, tau), dielectric(nb, 0.15f), lambertian(A)});
                    const size_t m = model_index(id);
                    const std::string why = model_cannot_represent(m, s);
                    if ((id.rfind("gltf", 0) == 0 && absorbs) || (id == "openpbr+dev1.2" && !absorbs)) {
                        EXPECT_NE(why, "") << id;
                        continue;
                    }
                    ASSERT_EQ(why, "") << id;
                    const DielectricBaseCase k(id, nb, ac, tau, A, s);
                    if (!k.gltf && ac == 0.3f && absorbs == 0) tables_checked += check_base_albedo_set(k);
                    check_dielectric_base(k, m, s);
                    checked += int(directions().size());
                }
    // openpbr, +pr261, +separable, +single, standard-surface, +osl: 3 IORs x 2 roughnesses x 2 absorptions; +dev1.2
    // absorbing only; glTF's two readings clear only
    EXPECT_EQ(checked, (6 * 12 + 6 + 2 * 6) * 36);
    EXPECT_EQ(tables_checked, 6 * 3 * 3);
    expect_white_dielectric_base_furnace();
}

// OpenPBR's coat_darkening (its file's `parameter:`, read as param_coat_darkening): the base scaled by lerp(1, Delta,
// delta), Delta = (1 - K_r) / (1 - E_b K_r) over a Lambertian (the specification's "Darkening", computed here again);
// the top lobe untouched; the default (1) the model as published; a value the model file does not declare refused
TEST(ProductionModels, OpenpbrCoatDarkeningIsItsParameter) {
    const glm::vec3 albedo(0.9f, 0.5f, 0.2f);
    const Stack s = make_stack("grey", {dielectric(1.5f, 0.2f), lambertian(albedo)});
    const size_t m = model_index("openpbr");
    const double eta = 1.5, k_r = 1 - (1 - exact::openpbr_fresnel_albedo(eta)) / (eta * eta);
    const ModelCpu published(m, pack_stack(s));
    int checked = 0;
    for (double delta : {0.0, 0.3, 1.0}) {
        ModelOptions o;
        o.parameters["openpbr"] = {delta};
        const ModelCpu at(m, pack_stack(s), o);
        for (const Direction& d : directions()) {
            const glm::vec3 l(float(d.l.x), float(d.l.y), float(d.l.z)), v(float(d.v.x), float(d.v.y), float(d.v.z));
            const glm::dvec3 top = at.value(l, v, kModelTermTop), top1 = published.value(l, v, kModelTermTop);
            const glm::dvec3 base = at.value(l, v, kModelTermBase), base1 = published.value(l, v, kModelTermBase);
            for (int c = 0; c < 3; ++c) {
                const double Delta = (1 - k_r) / (1 - albedo[c] * k_r);
                EXPECT_NEAR(top[c], top1[c], 1e-12);
                EXPECT_NEAR(base[c], base1[c] * ((1 - delta) + delta * Delta) / Delta, 1e-6 * base1[c] + 1e-9)
                    << "delta " << delta << " channel " << c;
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 30);
    ModelOptions two;
    two.parameters["openpbr"] = {0.5, 0.5};
    EXPECT_THROW(ModelCpu(m, pack_stack(s), two), std::invalid_argument);
}

// openpbr+numerator, #269's numerator (1 - E_F) / eta^2 = 1 - K_r in place of 1 - K: over a Lambertian (K = K_r) it is
// openpbr; over a metal the base term scales by (1 - K_r) / (1 - K), K = lerp(F(mu_v, eta), K_r, r_m), r_m =
// specular_roughness = sqrt(alpha_base) (the specification's K for a metal, computed here again); the top lobe untouched
TEST(ProductionModels, OpenpbrNumeratorIsTheErratum) {
    const double eta = 1.5, k_r = 1 - (1 - exact::openpbr_fresnel_albedo(eta)) / (eta * eta);
    const size_t published = model_index("openpbr"), erratum = model_index("openpbr+numerator");
    int checked = 0;
    for (int metal = 0; metal < 2; ++metal)
        for (float ab : {0.04f, 0.25f}) {
            const Stack s = make_stack(
                "base",
                {dielectric(1.5f, 0.1f), metal ? conductor(kCuN, kCuK, ab) : lambertian(glm::vec3(0.8f, 0.5f, 0.2f))});
            ASSERT_EQ(model_cannot_represent(erratum, s), "");
            const ModelCpu a(published, pack_stack(s)), b(erratum, pack_stack(s));
            for (const Direction& d : directions()) {
                const glm::vec3 l(float(d.l.x), float(d.l.y), float(d.l.z)),
                    v(float(d.v.x), float(d.v.y), float(d.v.z));
                const glm::dvec3 top = a.value(l, v, kModelTermTop), top_b = b.value(l, v, kModelTermTop);
                const glm::dvec3 base = a.value(l, v, kModelTermBase), base_b = b.value(l, v, kModelTermBase);
                const double K =
                    metal ? exact::fresnel(d.v.z, 1.0, eta) * (1 - std::sqrt(ab)) + k_r * std::sqrt(ab) : k_r;
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(top_b[c], top[c], 1e-12);
                    EXPECT_NEAR(base_b[c], base[c] * (1 - k_r) / (1 - K), 1e-5 * base[c] + 1e-9)
                        << (metal ? "metal" : "Lambertian") << " alpha " << ab << " channel " << c;
                }
                ++checked;
            }
        }
    EXPECT_GT(checked, 4 * 30);
}

// What they cannot take, each refused with its reason
TEST(ProductionModels, RefusalsWithReasons) {
    Stack dense = make_stack("dense-exterior", {dielectric(1.2f, 0.1f), lambertian(kAlbedo)});
    dense.exterior_ior = 1.5f;
    const std::string cycles = model_cannot_represent(model_index("cycles-principled"), dense);
    EXPECT_NE(cycles.find("clamps the Coat IOR to at least 1; this coat's IOR relative to the exterior is 0.8"),
              std::string::npos)
        << cycles;
    EXPECT_EQ(model_cannot_represent(model_index("openpbr-adobe"), dense), "");   // Adobe takes a coat below 1
    const Stack three = make_stack("three", {dielectric(1.5f, 0.1f), dielectric(1.3f, 0.1f), lambertian(kAlbedo)});
    for (const std::string id : {"cycles-principled", "openpbr-adobe", "interfaced-lambertian"})
        EXPECT_NE(model_cannot_represent(model_index(id), three).find("3 layers"), std::string::npos) << id;
    const size_t il = model_index("interfaced-lambertian");
    EXPECT_NE(model_cannot_represent(il, dense).find("denser than the medium above it"), std::string::npos);
    const Stack tinted = make_stack("tinted", {dielectric(1.5f, 0.1f, glm::vec3(0.2f)), lambertian(kAlbedo)});
    EXPECT_NE(model_cannot_represent(il, tinted)
                  .find("no medium between the interface and the Lambertian (layer 1's "
                        "medium absorbs"),
              std::string::npos)
        << model_cannot_represent(il, tinted);
    const Stack metal = make_stack("metal", {dielectric(1.5f, 0.1f), conductor(kCuN, kCuK, 0.2f)});
    EXPECT_NE(model_cannot_represent(il, metal).find("not over a conductor"), std::string::npos)
        << model_cannot_represent(il, metal);
}

}   // namespace
