// The sheen models (shaders/lib/models/builtin/16-zeltner22-sheen.glsl, 17-charlie-sheen.glsl) held to their authors'
// codes, transcribed again here in double: Zeltner, Burley & Chiang's pbrt-v3 SheenLTC (tizian/ltc-sheen @92624114
// pbrt-v3/src/materials/sheenltc.cpp: fetchCoeffs, rotateVector, evalLTC, f) reading the table from its CSV
// (data/sheen/ltc-sheen-volume-ltc.csv), OpenPBR's fuzz layering; KHR_materials_sheen's sheen BRDF and albedo
// scaling (KhronosGroup/glTF @60ad0f83), its E by a quadrature of the test's own. Then the LTC's normalisation (the
// lobe's albedo is C R), and which stacks the sheen models take and refuse, and why.
#include "model_twin_on_stack.h"
#include <gtest/gtest.h>
#include "model_applicability.h"
#include "models.h"
#include "stack.h"

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using namespace gonio;
using namespace gonio_test;

namespace {

const std::string kSource = GONIO_SOURCE_DIR;

size_t model_index(const std::string& id) {
    for (size_t i = 0; i < model_registry().size(); ++i)
        if (model_registry()[i].id == id) return i;
    throw std::runtime_error("no model " + id);
}

// The authors' table as data/sheen/ltc-sheen-volume-ltc.csv holds it: [alpha_index][mu_index] -> (a_inv, b_inv, R)
using LtcTable = std::array<std::array<std::array<double, 3>, 32>, 32>;
LtcTable read_ltc_csv() {
    std::ifstream in(kSource + "/data/sheen/ltc-sheen-volume-ltc.csv");
    if (!in) throw std::runtime_error("no data/sheen/ltc-sheen-volume-ltc.csv");
    LtcTable t{};
    std::string line;
    int rows = 0;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#' || line.rfind("mu_index", 0) == 0) continue;
        std::stringstream ss(line);
        std::string c[7];
        for (auto& x : c) std::getline(ss, x, ',');
        const int i = std::stoi(c[0]), j = std::stoi(c[1]);
        for (int k = 0; k < 3; ++k) t[size_t(j)][size_t(i)][size_t(k)] = std::strtod(c[4 + k].c_str(), nullptr);
        ++rows;
    }
    if (rows != 1024) throw std::runtime_error("the LTC table has " + std::to_string(rows) + " rows");
    return t;
}

struct D3 {
    double x, y, z;
};
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 normalized(D3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }

// sheenltc.cpp fetchCoeffs: bilinear over the table's nodes, row = alpha x 31, col = cos(theta_o) x 31
std::array<double, 3> fetch_coeffs(const LtcTable& t, double alpha, double cos_o) {
    const double one_minus_eps = 0x1.fffffep-1;
    const double row = std::max(0.0, std::min(alpha, one_minus_eps)) * 31,
                 col = std::max(0.0, std::min(cos_o, one_minus_eps)) * 31;
    const int r = int(std::floor(row)), c = int(std::floor(col));
    const double rf = row - r, cf = col - c;
    std::array<double, 3> out{};
    for (int k = 0; k < 3; ++k)
        out[size_t(k)] =
            (t[size_t(r)][size_t(c)][size_t(k)] * (1 - cf) + t[size_t(r)][size_t(c + 1)][size_t(k)] * cf) * (1 - rf) +
            (t[size_t(r + 1)][size_t(c)][size_t(k)] * (1 - cf) + t[size_t(r + 1)][size_t(c + 1)][size_t(k)] * cf) * rf;
    return out;
}

// sheenltc.cpp SheenLTC::f(wo, wi) x cos(theta_i) / Csheen / R: wo the view, wi the light
double sheen_ltc_f_cos(const std::array<double, 3>& coeffs, D3 wo, D3 wi) {
    double phi = std::atan2(wo.y, wo.x);
    if (phi < 0) phi += 2 * M_PI;
    const D3 axis{0, 0, 1};   // rotateVector(wi, z, -phi)
    const double s = std::sin(-phi), c = std::cos(-phi);
    const D3 w = wi * c + axis * (dot(wi, axis) * (1 - c)) + cross(axis, wi) * s;
    const double a_inv = coeffs[0], b_inv = coeffs[1];
    D3 o{a_inv * w.x + b_inv * w.z, a_inv * w.y, w.z};
    const double length = std::sqrt(dot(o, o));
    o = o * (1 / length);
    const double jacobian = a_inv * a_inv / (length * length * length);
    return std::max(o.z, 0.0) / M_PI * jacobian;   // CosineHemispherePdf
}

// KHR_materials_sheen: the Charlie distribution, lambda_sheen and sheen_visibility, in double
double gltf_charlie_D(double alpha, double n_dot_h) {
    const double inv_r = 1 / alpha, sin2h = 1 - n_dot_h * n_dot_h;
    return (2 + inv_r) * std::pow(sin2h, inv_r * 0.5) / (2 * M_PI);
}
double gltf_l(double x, double alpha) {
    const double one_minus_alpha_sq = (1 - alpha) * (1 - alpha);
    auto mix = [](double a, double b, double t) { return a * (1 - t) + b * t; };
    const double a = mix(21.5473, 25.3245, one_minus_alpha_sq), b = mix(3.82987, 3.32435, one_minus_alpha_sq);
    const double c = mix(0.19823, 0.16801, one_minus_alpha_sq), d = mix(-1.97760, -1.27393, one_minus_alpha_sq);
    const double e = mix(-4.32054, -4.85967, one_minus_alpha_sq);
    return a / (1 + b * std::pow(x, c)) + d * x + e;
}
double gltf_lambda_sheen(double cos_theta, double alpha) {
    return std::abs(cos_theta) < 0.5 ? std::exp(gltf_l(cos_theta, alpha))
                                     : std::exp(2 * gltf_l(0.5, alpha) - gltf_l(1 - cos_theta, alpha));
}
double gltf_sheen_brdf(D3 l, D3 v, double alpha) {
    const D3 h = normalized(l + v);
    const double vis = 1 / ((1 + gltf_lambda_sheen(v.z, alpha) + gltf_lambda_sheen(l.z, alpha)) * (4 * v.z * l.z));
    return gltf_charlie_D(alpha, h.z) * vis;
}
// E(mu): the white lobe's directional albedo, by the midpoint rule in theta_v and phi_v (the test's own quadrature)
double gltf_sheen_albedo(double mu, double alpha) {
    const D3 l{std::sqrt(1 - mu * mu), 0, mu};
    const int nt = 400, np = 400;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) * M_PI / 2 / nt;
        for (int k = 0; k < np; ++k) {
            const double p = (k + 0.5) * 2 * M_PI / np;
            const D3 v{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
            sum += gltf_sheen_brdf(l, v, alpha) * v.z * std::sin(t);
        }
    }
    return sum * (M_PI / 2 / nt) * (2 * M_PI / np);
}

// The directions of the check: l at theta_i = 0, 35, 70, 85 degrees in the x-z plane, v at theta_o = 10, 40, 75, 88
// degrees and azimuths 0, 60, 180 degrees
std::vector<std::pair<D3, D3>> directions() {
    std::vector<std::pair<D3, D3>> out;
    for (double ti : {0.0, 35.0, 70.0, 85.0})
        for (double to : {10.0, 40.0, 75.0, 88.0})
            for (double phi : {0.0, 60.0, 180.0}) {
                const double a = ti * M_PI / 180, b = to * M_PI / 180, p = phi * M_PI / 180;
                out.push_back({{std::sin(a), 0, std::cos(a)},
                               {std::sin(b) * std::cos(p), std::sin(b) * std::sin(p), std::cos(b)}});
            }
    return out;
}

// A fibre layer of roughness alpha and colour `colour` over a Lambertian of albedo `base`
Stack fibres_over_lambertian(double alpha, const std::string& colour, const std::string& base,
                             const std::string& optical_depth = "1.0", const std::string& top = "") {
    return parse_stack_string(
        "name = \"fibres\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nior = 1.0\n" + top +
            "optical_depth = " + optical_depth + "\nscattering_albedo = " + colour +
            "\nphase = \"sggx-fibre\"\nfibre_roughness = " + std::to_string(alpha) +
            "\n[[layer]]\ninterface = \"lambertian\"\nalbedo = " + base + "\n",
        "fibres.toml");
}

glm::vec3 fv(D3 a) { return glm::vec3(float(a.x), float(a.y), float(a.z)); }

}   // namespace

// The array the model's host hook reads is the CSV's table, value by value (tools/ltc_sheen/ltc_table.py writes both)
TEST(SheenModels, Zeltner22TableIsTheAuthorsCsv) {
    const LtcTable t = read_ltc_csv();
    for (size_t j = 0; j < 32; ++j)
        for (size_t i = 0; i < 32; ++i)
            for (size_t k = 0; k < 3; ++k)
                ASSERT_EQ(ZELTNER22_LTC_TABLE[j][i][k], float(t[j][i][k])) << "alpha " << j << " mu " << i << " " << k;
}

// f = C R LTC / mu_l + (1 - R) albedo / pi, R and the LTC as sheenltc.cpp computes them from the CSV's table
TEST(SheenModels, Zeltner22IsTheAuthorsCode) {
    const LtcTable t = read_ltc_csv();
    const size_t m = model_index("zeltner22-sheen");
    const std::array<double, 3> colour{0.9, 0.6, 0.55}, base{0.35, 0.05, 0.5};
    int checked = 0;
    for (double alpha : {0.05, 0.3, 0.5, 0.77, 1.0}) {
        const Stack s = fibres_over_lambertian(alpha, "[0.9, 0.6, 0.55]", "[0.35, 0.05, 0.5]");
        ASSERT_EQ(model_cannot_represent(m, s), "");
        const ModelCpu cpu(m, pack_stack(s));
        for (const auto& [l, v] : directions()) {
            const std::array<double, 3> k = fetch_coeffs(t, float(alpha), v.z);
            const double lobe = sheen_ltc_f_cos(k, v, l) / l.z * k[2];
            const glm::dvec3 got = cpu.value(fv(l), fv(v));
            for (int c = 0; c < 3; ++c) {
                const double want = colour[size_t(c)] * lobe + base[size_t(c)] / M_PI * (1 - k[2]);
                ASSERT_NEAR(got[c], want, 2e-4 * want + 1e-6) << "alpha " << alpha << " l.z " << l.z << " v " << v.x
                                                              << " " << v.y << " " << v.z << " channel " << c;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 5 * 48 * 3);
}

// The LTC integrates to 1 over the hemisphere of l (w.z = l.z: nothing of it lies below), so the lobe's albedo seen
// from v is C R(mu_v): a test of the Jacobian a_inv^2 / |w|^3 the transcription above shares with the model
TEST(SheenModels, Zeltner22LobeHoldsTheSlabsReflectance) {
    const LtcTable t = read_ltc_csv();
    const size_t m = model_index("zeltner22-sheen");
    for (double alpha : {0.35, 0.6, 1.0}) {
        const Stack s = fibres_over_lambertian(alpha, "1.0", "0.0");
        const ModelCpu cpu(m, pack_stack(s));
        for (double mu_v : {0.2, 0.6, 0.95}) {
            const D3 v{std::sqrt(1 - mu_v * mu_v) * std::cos(0.7), std::sqrt(1 - mu_v * mu_v) * std::sin(0.7), mu_v};
            const int nt = 600, np = 600;
            double sum = 0;
            for (int i = 0; i < nt; ++i) {
                const double th = (i + 0.5) * M_PI / 2 / nt;
                for (int k = 0; k < np; ++k) {
                    const double p = (k + 0.5) * 2 * M_PI / np;
                    const D3 l{std::sin(th) * std::cos(p), std::sin(th) * std::sin(p), std::cos(th)};
                    sum += cpu.value(fv(l), fv(v)).x * l.z * std::sin(th);
                }
            }
            sum *= (M_PI / 2 / nt) * (2 * M_PI / np);
            const double r = fetch_coeffs(t, float(alpha), float(mu_v))[2];
            EXPECT_NEAR(sum, r, 2e-3 * r) << "alpha " << alpha << " mu_v " << mu_v;
        }
    }
}

// The lobe is KHR_materials_sheen's sheen BRDF times the colour; the base is scaled by
// max(min(1 - max(C) E(mu_v), 1 - max(C) E(mu_l)), 0), E the white lobe's albedo by the test's own quadrature (at the model's
// table nodes; SheenModels.CharlieAlbedoSetIsTheLobesAlbedo holds the nodes themselves): charlie-sheen at
// the fibres' alpha, gltf-sheen at its square (alpha_g = sheenRoughness^2, sheenRoughness the fibres' alpha)
TEST(SheenModels, CharlieAndGltfAreTheGltfCode) {
    const std::array<double, 3> colour{0.9, 0.6, 0.55}, base{0.35, 0.05, 0.5};
    for (const std::string id : {"charlie-sheen", "gltf-sheen"}) {
        const size_t m = model_index(id);
        for (double alpha : {0.1, 0.3, 0.5, 1.0}) {
            const Stack s = fibres_over_lambertian(alpha, "[0.9, 0.6, 0.55]", "[0.35, 0.05, 0.5]");
            ASSERT_EQ(model_cannot_represent(m, s), "");
            const ModelCpu cpu(m, pack_stack(s));
            const double alpha_g =
                id == "gltf-sheen" ? double(float(alpha)) * double(float(alpha)) : double(float(alpha));
            // E as the model reads its table: linear between the nodes mu = i / 128 (node 0 at 1e-4), each node the
            // test's own quadrature, within 1e-3 of the model's (CharlieAlbedoSetIsTheLobesAlbedo; E is 1.29 at
            // mu 0.035 for alpha_g 0.01)
            std::map<uint32_t, double> node;
            auto e_at = [&](double mu) {
                const double x = std::clamp(mu, 0.0, 1.0) * 128;
                const uint32_t i = std::min(uint32_t(x), 127u);
                for (uint32_t k : {i, i + 1})
                    if (!node.count(k)) node[k] = gltf_sheen_albedo(std::max(k / 128.0, 1e-4), alpha_g);
                return node[i] + (node[i + 1] - node[i]) * (x - i);
            };
            for (const auto& [l, v] : directions()) {
                const double lobe = gltf_sheen_brdf(l, v, alpha_g);
                const double scale = std::max(std::min(1 - 0.9 * e_at(v.z), 1 - 0.9 * e_at(l.z)), 0.0);
                const glm::dvec3 top = cpu.value(fv(l), fv(v), 1u), all = cpu.value(fv(l), fv(v));
                for (int c = 0; c < 3; ++c) {
                    ASSERT_NEAR(top[c], colour[size_t(c)] * lobe, 2e-4 * colour[size_t(c)] * lobe + 1e-7)
                        << id << " alpha " << alpha << " l.z " << l.z << " v.z " << v.z;
                    ASSERT_NEAR(all[c] - top[c], base[size_t(c)] / M_PI * scale, 2e-3 * base[size_t(c)] / M_PI)
                        << id << " alpha " << alpha << " l.z " << l.z << " v.z " << v.z;
                }
            }
        }
    }
}

// MaterialX's sheen_bsdf as mx_sheen_bsdf.glsl and lib/mx_microfacet_sheen.glsl compute it (@4177b2cb), in double:
// mode zeltner (materialx-sheen, OpenPBR's reference graph) and mode conty_kulla (standard-surface-sheen), layered
// over the diffuse by mx_layer_bsdf (response / n.l + throughput albedo / pi)
double mx_square(double x) { return x * x; }
double mx_zeltner_sheen_dir_albedo(double x, double y) {
    const double s = y * (0.0206607 + 1.58491 * y) / (0.0379424 + y * (1.32227 + y));
    const double m = y * (-0.193854 + y * (-1.14885 + y * (1.7932 - 0.95943 * y * y))) / (0.046391 + y);
    const double o = y * (0.000654023 + (-0.0207818 + 0.119681 * y) * y) / (1.26264 + y * (-1.92021 + y));
    return std::exp(-0.5 * mx_square((x - m) / s)) / (s * std::sqrt(2.0 * M_PI)) + o;
}
double mx_zeltner_sheen_brdf(D3 L, D3 V, double NdotV, double roughness) {
    D3 X = V + D3{0, 0, 1} * -NdotV;   // mx_orthonormal_basis_ltc
    const double len_sqr = dot(X, X);
    X = len_sqr > 0 ? X * (1 / std::sqrt(len_sqr)) : D3{1, 0, 0};
    const D3 Y = cross(D3{0, 0, 1}, X);
    const D3 w{dot(X, L), dot(Y, L), L.z};
    const double x = NdotV, y = roughness;
    const double a_inv = (2.58126 * x + 0.813703 * y) * y / (1.0 + 0.310327 * x * x + 2.60994 * x * y);
    const double b_inv =
        std::sqrt(1.0 - x) * (y - 1.0) * y * y * y / (0.0000254053 + 1.71228 * x - 1.71506 * x * y + 1.34174 * y * y);
    const D3 wo{a_inv * w.x + b_inv * w.z, a_inv * w.y, w.z};
    return std::max(wo.z, 0.0) / M_PI * mx_square(a_inv / dot(wo, wo));
}
double mx_imageworks_sheen_brdf(double NdotL, double NdotV, double NdotH, double roughness) {
    const double inv_roughness = 1.0 / std::max(roughness, 0.005);
    const double d = (2.0 + inv_roughness) * std::pow(1.0 - NdotH * NdotH, inv_roughness * 0.5) / (2.0 * M_PI);
    return d / (4.0 * (NdotL + NdotV - NdotL * NdotV));
}
double mx_imageworks_sheen_dir_albedo(double NdotV, double r) {
    const double px = 13.67300 - 68.78018 * NdotV + 799.08825 * r - 905.00061 * NdotV * r + 60.28956 * NdotV * NdotV +
                      1086.96473 * r * r;
    const double py = 1.0 + 61.57746 * NdotV + 442.78211 * r + 2597.49308 * NdotV * r + 121.81241 * NdotV * NdotV +
                      3045.55075 * r * r;
    return std::clamp(px / py, 0.0, 1.0);
}

TEST(SheenModels, MaterialxSheenModesAreItsCode) {
    const std::array<double, 3> colour{0.9, 0.6, 0.55}, base{0.35, 0.05, 0.5};
    for (const std::string id : {"materialx-sheen", "standard-surface-sheen"}) {
        const size_t m = model_index(id);
        for (double alpha : {0.05, 0.3, 0.5, 1.0}) {
            const Stack s = fibres_over_lambertian(alpha, "[0.9, 0.6, 0.55]", "[0.35, 0.05, 0.5]");
            ASSERT_EQ(model_cannot_represent(m, s), "");
            const ModelCpu cpu(m, pack_stack(s));
            const double r = double(float(alpha));
            for (const auto& [l, v] : directions()) {
                const double nv = std::clamp(v.z, 1e-8, 1.0), nl = std::clamp(l.z, 1e-8, 1.0);
                double lobe, e;
                if (id == "materialx-sheen") {
                    const double y = std::clamp(r, 0.01, 1.0);
                    e = std::max(mx_zeltner_sheen_dir_albedo(nv, y), 0.0);   // gonio's clamp (the model's file)
                    lobe = e * mx_zeltner_sheen_brdf(l, v, nv, y) / l.z;
                } else {
                    e = mx_imageworks_sheen_dir_albedo(nv, r);
                    lobe = mx_imageworks_sheen_brdf(nl, nv, std::clamp(normalized(l + v).z, 1e-8, 1.0), r);
                }
                const glm::dvec3 got = cpu.value(fv(l), fv(v));
                for (int c = 0; c < 3; ++c) {
                    const double want = colour[size_t(c)] * lobe + base[size_t(c)] / M_PI * (1 - e);
                    ASSERT_NEAR(got[c], want, 3e-4 * want + 1e-6)
                        << id << " alpha " << alpha << " l.z " << l.z << " v " << v.x << " " << v.y << " " << v.z;
                }
            }
        }
    }
}

// Cycles' sheen: the table read at (cos N.I, roughness) as lookup_table_read_2D reads it, the closure's weight the
// tint times R, the diffuse scaled by saturate(1 - max(tint R))
TEST(SheenModels, CyclesSheenIsItsClosureCode) {
    const LtcTable t = read_ltc_csv();
    const size_t m = model_index("cycles-sheen");
    const std::array<double, 3> tint{0.9, 0.6, 0.55}, base{0.35, 0.05, 0.5};
    for (double alpha : {0.05, 0.3, 0.77, 1.0}) {
        const Stack s = fibres_over_lambertian(alpha, "[0.9, 0.6, 0.55]", "[0.35, 0.05, 0.5]");
        ASSERT_EQ(model_cannot_represent(m, s), "");
        const ModelCpu cpu(m, pack_stack(s));
        for (const auto& [l, v] : directions()) {
            // lookup_table_read_2D(x = cos N.I, y = roughness): nodes i / 31, the upper node clamped
            const double x = std::clamp(v.z, 0.0, 1.0) * 31, y = std::clamp(double(float(alpha)), 1e-3, 1.0) * 31;
            const int ix = std::min(int(x), 31), iy = std::min(int(y), 31);
            const int nx = std::min(ix + 1, 31), ny = std::min(iy + 1, 31);
            const double tx = x - ix, ty = y - iy;
            std::array<double, 3> k{};
            for (size_t q = 0; q < 3; ++q)
                k[q] = (1 - ty) * ((1 - tx) * t[size_t(iy)][size_t(ix)][q] + tx * t[size_t(iy)][size_t(nx)][q]) +
                       ty * ((1 - tx) * t[size_t(ny)][size_t(ix)][q] + tx * t[size_t(ny)][size_t(nx)][q]);
            const double lobe = sheen_ltc_f_cos(k, v, l) / l.z * k[2];
            const double scale = std::clamp(1 - 0.9 * k[2], 0.0, 1.0);
            const glm::dvec3 got = cpu.value(fv(l), fv(v));
            for (int c = 0; c < 3; ++c) {
                const double want = tint[size_t(c)] * lobe + base[size_t(c)] / M_PI * scale;
                ASSERT_NEAR(got[c], want, 2e-4 * want + 1e-6)
                    << "alpha " << alpha << " l.z " << l.z << " v " << v.x << " " << v.y << " " << v.z;
            }
        }
    }
}

// The charlie-albedo set: E(mu) at its nodes against the test's own quadrature
TEST(SheenModels, CharlieAlbedoSetIsTheLobesAlbedo) {
    for (double alpha : {0.05, 0.4, 1.0}) {
        const Stack s = fibres_over_lambertian(alpha, "1.0", "0.5");
        const std::vector<float> t = stack_tables(pack_stack(s), STACK_TABLES_CHARLIE_ALBEDO);
        for (uint32_t i = 0; i < CHARLIE_ALBEDO_NODES; i += 8) {   // every 8th node (1/16 apart), both ends
            const double mu = std::max(double(i) / (CHARLIE_ALBEDO_NODES - 1), double(SHEEN_ALBEDO_MU_MIN));
            const double want = gltf_sheen_albedo(mu, float(alpha));
            EXPECT_NEAR(t[STACK_TABLE_CHARLIE_ALBEDO + i], want, 2e-4 + 1e-3 * want)
                << "alpha " << alpha << " mu " << mu;
        }
    }
}

// The sheen models take a fibre layer over a Lambertian, and only that; every other model refuses the fibres
TEST(SheenModels, WhatTheyTakeAndWhy) {
    const size_t z = model_index("zeltner22-sheen"), c = model_index("charlie-sheen");
    const Stack velvet = parse_stack_file(kSource + "/stacks/velvet.toml");
    for (size_t m = 0; m < model_registry().size(); ++m)
        if (model_registry()[m].header.family == "sheen") {
            EXPECT_EQ(model_cannot_represent(m, velvet), "") << model_registry()[m].id;
        } else {
            const std::string why = model_cannot_represent(m, velvet);
            EXPECT_NE(why, "") << model_registry()[m].id;
        }
    EXPECT_NE(model_cannot_represent(model_index("openpbr"), velvet).find("Henyey-Greenstein"), std::string::npos);
    const std::string thick = model_cannot_represent(z, fibres_over_lambertian(0.5, "1.0", "0.5", "2.0"));
    EXPECT_NE(thick.find("unit slab"), std::string::npos) << thick;
    EXPECT_NE(thick.find("optical depth is 2"), std::string::npos) << thick;
    const std::string plastic = model_cannot_represent(c, parse_stack_file(kSource + "/stacks/plastic.toml"));
    EXPECT_NE(plastic.find("fibres-over-lambertian"), std::string::npos) << plastic;
    // a rough or a refracting top is not the fibres' open top
    EXPECT_NE(model_cannot_represent(z, fibres_over_lambertian(0.5, "1.0", "0.5", "1.0", "roughness = 0.1\n")), "");
    const Stack dense = parse_stack_string(
        "name = \"t\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\noptical_depth = 1.0\nscattering_albedo = "
        "1.0\nphase = \"sggx-fibre\"\nfibre_roughness = 0.5\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n",
        "dense.toml");
    EXPECT_NE(model_cannot_represent(c, dense), "");
    // flakes are not fibres
    const Stack flakes = parse_stack_string(
        "name = \"t\"\nexterior_ior = 1.0\n[[layer]]\ninterface = \"dielectric\"\nior = 1.0\noptical_depth = 1.0\nscattering_albedo = "
        "1.0\nphase = \"sggx-flake\"\nfibre_roughness = 0.5\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n",
        "flakes.toml");
    EXPECT_NE(model_cannot_represent(z, flakes), "");
}
