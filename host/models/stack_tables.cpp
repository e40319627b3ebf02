// stack_tables.cpp: see stack_tables.h.
#include "stack_tables.h"
#include "model_twin.h"

#include <algorithm>
#include <cmath>

namespace gonio {

std::vector<float> coat_albedo_table(const StackGpu& sg) {
    // E_coat(mu) = the integral of f_r0(l, v) cos(theta_v) dv over the hemisphere (common.glsl's top_reflection:
    // dielectric Fresnel, GGX D, height-correlated G2), at the table's nodes of mu: the FGD of the coat's interface
    // with G2, by gonio's one quadrature of an interface's albedo (models/fgd_quadrature.glsl, which Belcour's
    // tables also call). mu = 0 is its limit mu -> 0+. Clamped to 1, so that
    // 1 - E_coat, the base's weight, is never negative.
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    std::vector<float> table(COAT_ALBEDO_NODES);
    for (uint i = 0; i < COAT_ALBEDO_NODES; ++i)
        table[i] = std::min(
            1.0f,
            fgd_quadrature(sg.layers[0], coat_albedo_node_mu(i), p.alpha0, true, FGD_NODES_THETA, FGD_NODES_PHI).x);
    return table;
}

namespace {

// The body table's quadrature over the visible normals (sample_ggx_visible_normal's square: the periodic azimuth by
// the midpoint rule, the cap's height by Gauss-Legendre): 64 x 32 nodes are within 1e-4 of the body (4.3e-4 at
// alpha 0.8) where the midpoint rule on 32 x 32 was 9e-3 off (at alpha 0.05; against 512 x 512 midpoint nodes)
constexpr uint32_t kInterfacedAzimuthNodes = 64, kInterfacedCapNodes = 32;

// Gauss-Legendre nodes and weights on [0, 1] (Newton on the Legendre polynomial)
void gauss_legendre(uint32_t n, std::vector<double>& x, std::vector<double>& w) {
    x.resize(n);
    w.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1, p2 = 0;
            for (uint32_t j = 0; j < n; ++j) {
                const double p3 = p2;
                p2 = p1;
                p1 = ((2.0 * j + 1) * z * p2 - j * p3) / (j + 1);
            }
            dp = n * (z * p1 - p2) / (z * z - 1);
            const double step = p1 / dp;
            z -= step;
            if (std::fabs(step) < 1e-15) break;
        }
        x[i] = 0.5 * (1 - z);
        w[i] = 1.0 / ((1 - z * z) * dp * dp);
    }
}

// The body's mean over the visible normals of a
double interfaced_body_quadrature(vec3 a, vec3 b, float eta, float alpha, uint32_t n_az, uint32_t n_cap) {
    std::vector<double> x, w;
    gauss_legendre(n_cap, x, w);
    double sum = 0;
    for (uint32_t j = 0; j < n_cap; ++j) {
        double row = 0;
        for (uint32_t i = 0; i < n_az; ++i)
            row += interfaced_body_integrand(
                a, b, sample_ggx_visible_normal(a, alpha, (float(i) + 0.5f) / float(n_az), float(x[j])), eta, alpha);
        sum += w[j] * row / n_az;
    }
    return sum;
}

// A smooth dielectric interface of relative IOR eta, as gonio's quadrature of an albedo takes it (kind and eta)
LayerGpu dielectric_interface(float eta) {
    LayerGpu L{};
    L.p0 = vec4(float(KIND_DIELECTRIC), 0.0f, eta, 1.0f / eta);
    return L;
}

// The quadrature's sums at (eta, alpha, mu) with masking g_mode (fgd_quadrature.glsl); below the quadrature's
// smallest roughness (MODEL_MIN_ALPHA: Adobe's roughness node 0, Cycles' 1e-4, alpha 1e-8) the smooth interface's:
// its Fresnel at mu, the whole lobe (the tables' own values there: exact Fresnel, ggx_E = 1)
FgdSums sums_at(float eta, float alpha, float mu, uint g_mode) {
    if (alpha < MODEL_MIN_ALPHA) {
        FgdSums smooth;
        const float f = fresnel_dielectric(mu, eta), f0 = (eta - 1.0f) * (eta - 1.0f) / ((eta + 1.0f) * (eta + 1.0f));
        smooth.fgd = vec3((g_mode & FGD_FRESNEL_REMAPPED) != 0u ? std::clamp((f - f0) / (1.0f - f0), 0.0f, 1.0f) : f);
        smooth.lobe = 1.0f;
        smooth.tir = 1.0f;
        return smooth;
    }
    // below IOR 1 the Fresnel steps to 1 at the critical angle, which the midpoint rule in phi_m crosses: 256 nodes
    // there (32: 6.2e-4 off at Adobe's OD[8][12][25], IOR 1 / 1.7; 256: 8e-5)
    return fgd_quadrature_sums(dielectric_interface(eta), mu, alpha, g_mode, FGD_NODES_THETA,
                               eta < 1.0f ? 8u * FGD_NODES_PHI : FGD_NODES_PHI);
}

// 2 int_0^1 e(mu) mu dmu by 24-point Gauss-Legendre in mu: the cosine-weighted average of a directional albedo
// (Adobe's average complements, Cycles' ggx_Eavg), as their tables define it
template <class E>
double cosine_average(E e) {
    static const double x[12] = {0.0640568928626056, 0.1911188674736163, 0.3150426796961634, 0.4337935076260451,
                                 0.5454214713888396, 0.6480936519369755, 0.7401241915785544, 0.8200019859739029,
                                 0.8864155270044010, 0.9382745520027328, 0.9747285559713095, 0.9951872199970214};
    static const double w[12] = {0.1279381953467522, 0.1258374563468283, 0.1216704729278034, 0.1155056680537256,
                                 0.1074442701159656, 0.0976186521041139, 0.0861901615319533, 0.0733464814110803,
                                 0.0592985849154368, 0.0442774388174198, 0.0285313886289337, 0.0123412297999872};
    double sum = 0.0;
    for (int i = 0; i < 12; ++i)
        for (int s = -1; s <= 1; s += 2) {
            const double mu = 0.5 * (1.0 + s * x[i]);
            sum += 0.5 * w[i] * 2.0 * mu * e(float(mu));
        }
    return sum;
}

// The two nodes of an axis an exact index falls between and the weight of the upper one, as the authors' lookups
// take them: clamped to [0, nodes - 1], the upper node min(lower + 1, nodes - 1)
struct AxisCell {
    uint lo, hi;
    float t;
};
AxisCell axis_cell(float exact_index, uint nodes) {
    const float x = std::clamp(exact_index, 0.0f, float(nodes - 1u));
    const uint lo = uint(std::floor(x));
    return {lo, std::min(lo + 1u, nodes - 1u), x - float(lo)};
}

// adobe-energy: the stack's coat albedo E_c(mu_k) = 1 - OD(eta_c, alpha_c, mu_k), the diffuse's OD(1, alpha'_s, mu_k)
// and ODA, the metal's IM(alpha'_s, mu_k) and IMA, each interpolated in IOR and roughness as Adobe's trilinear and
// bilinear lookups are, from gonio's quadrature at Adobe's nodes (adobe_opaque_dielectric_complement etc.)
void adobe_tables(const StackGpu& sg, std::vector<float>& t) {
    const CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    const AxisCell ior = axis_cell(adobe_ior_index(p.eta), ADOBE_TABLE_NODES);
    const AxisCell rc = axis_cell(adobe_alpha_index(adobe_alpha(p.alpha0)), ADOBE_TABLE_NODES);
    const float extrapolation = adobe_ior_extrapolation(p.eta);
    for (uint k = 0; k < ADOBE_TABLE_NODES; ++k) {
        auto od = [&](uint i, uint j) { return adobe_opaque_dielectric_complement(i, j, k); };
        const float lo = od(ior.lo, rc.lo) + (od(ior.hi, rc.lo) - od(ior.lo, rc.lo)) * ior.t;
        const float hi = rc.t > 0.0f ? od(ior.lo, rc.hi) + (od(ior.hi, rc.hi) - od(ior.lo, rc.hi)) * ior.t : lo;
        t[STACK_TABLE_ADOBE_COAT + k] = 1.0f - extrapolation * (lo + (hi - lo) * rc.t);
    }
    // the base's tables at IOR 1 (index 16, exactly a node) and alpha'_s = r'^2
    const float r = adobe_roughened(p);
    const AxisCell rs = axis_cell(adobe_alpha_index(r * r), ADOBE_TABLE_NODES);
    auto along_r = [&](auto table) {
        return table(rs.lo) + (rs.t > 0.0f ? (table(rs.hi) - table(rs.lo)) * rs.t : 0.0f);
    };
    const bool metal = p.base_kind == KIND_CONDUCTOR;
    for (uint k = 0; k < ADOBE_TABLE_NODES; ++k) {
        if (metal)
            t[STACK_TABLE_ADOBE_METAL + k] = along_r([&](uint j) { return adobe_ideal_metal_complement(j, k); });
        else
            t[STACK_TABLE_ADOBE_DIFFUSE + k] =
                along_r([&](uint j) { return adobe_opaque_dielectric_complement(16u, j, k); });
    }
    if (metal)
        t[STACK_TABLE_ADOBE_METAL + ADOBE_TABLE_NODES] =
            along_r([&](uint j) { return adobe_ideal_metal_average_complement(j); });
    else
        t[STACK_TABLE_ADOBE_DIFFUSE + ADOBE_TABLE_NODES] =
            along_r([&](uint j) { return adobe_opaque_dielectric_average_complement(16u, j); });
}

// cycles-energy: ggx_E and ggx_Eavg at the coat's roughness and the base's, and ggx_gen_schlick_ior_s at the coat's
// roughness and z, interpolated as lookup_table_read_2D / 3D are
void cycles_tables(const StackGpu& sg, std::vector<float>& t) {
    const CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    auto e_set = [&](uint offset, float alpha) {
        const AxisCell r =
            axis_cell(std::clamp(std::sqrt(alpha), 0.0f, 1.0f) * float(CYCLES_E_NODES - 1u), CYCLES_E_NODES);
        auto along_r = [&](auto table) {
            return table(r.lo) + (r.t > 0.0f ? (table(r.hi) - table(r.lo)) * r.t : 0.0f);
        };
        for (uint j = 0; j < CYCLES_E_NODES; ++j) t[offset + j] = along_r([&](uint i) { return cycles_ggx_e(i, j); });
        t[offset + CYCLES_E_NODES] = along_r([&](uint i) { return cycles_ggx_e_avg(i); });
    };
    e_set(STACK_TABLE_CYCLES_COAT_E, adobe_alpha(p.alpha0));
    if (p.base_kind == KIND_CONDUCTOR) e_set(STACK_TABLE_CYCLES_BASE_E, adobe_alpha(p.alpha1));
    if (!(p.eta > 1.0f)) return;   // the coat's albedo estimate reads the table above IOR 1 only
    const float n = float(CYCLES_S_NODES - 1u);
    const AxisCell r = axis_cell(std::clamp(std::sqrt(adobe_alpha(p.alpha0)), 0.0f, 1.0f) * n, CYCLES_S_NODES);
    const AxisCell z =
        axis_cell(std::clamp(std::sqrt(std::fabs((p.eta - 1.0f) / (p.eta + 1.0f))), 0.0f, 1.0f) * n, CYCLES_S_NODES);
    for (uint j = 0; j < CYCLES_S_NODES; ++j) {
        auto s = [&](uint i, uint k) { return cycles_schlick_ior_s(i, j, k); };
        const float lo = s(r.lo, z.lo) + (r.t > 0.0f ? (s(r.hi, z.lo) - s(r.lo, z.lo)) * r.t : 0.0f);
        const float hi = z.t > 0.0f ? s(r.lo, z.hi) + (r.t > 0.0f ? (s(r.hi, z.hi) - s(r.lo, z.hi)) * r.t : 0.0f) : lo;
        t[STACK_TABLE_CYCLES_COAT_S + j] = lo + (hi - lo) * z.t;
    }
}

// interfaced-body: r_i = 1 - (1 - r_e) / eta^2 with r_e = 2 int F(mu, eta) mu dmu, and the body's mean over
// visible normals B at the table's nodes less its flat part, each node pair once (symmetric by construction), the mean
// taken over the visible normals of the more grazing of the two directions (its masking's edge is then inside the
// cap's map)
void interfaced_tables(const StackGpu& sg, std::vector<float>& t) {
    const CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    t[STACK_TABLE_INTERFACED_RI] = interfaced_internal_reflectance(p.eta);
    for (uint i = 0; i < IL_MU_NODES; ++i)
        for (uint j = i; j < IL_MU_NODES; ++j)
            for (uint k = 0; k < IL_PHI_NODES; ++k) {
                const float b =
                    interfaced_body_node(p.eta, p.alpha0, i, j, k, kInterfacedAzimuthNodes, kInterfacedCapNodes) -
                    interfaced_flat_body(interfaced_mu_node(i), interfaced_mu_node(j), p.eta);
                t[STACK_TABLE_INTERFACED_BODY + (i * IL_MU_NODES + j) * IL_PHI_NODES + k] = b;
                t[STACK_TABLE_INTERFACED_BODY + (j * IL_MU_NODES + i) * IL_PHI_NODES + k] = b;
            }
}

// The directional albedo of a dielectric interface of relative IOR eta and GGX alpha (its reflection alone; masking
// g_mode: FGD_G2 or FGD_SEPARABLE) at the coat-albedo nodes into t from `offset`, clamped to 1 (1 - E weighs what lies
// below): gonio's one quadrature
void interface_albedo(float eta, float alpha, uint32_t offset, std::vector<float>& t, uint g_mode = FGD_G2) {
    for (uint i = 0; i < COAT_ALBEDO_NODES; ++i)
        t[offset + i] =
            std::min(1.0f, sums_at(eta, std::max(alpha, MODEL_MIN_ALPHA), coat_albedo_node_mu(i), g_mode).fgd.x);
}

// openpbr-base-albedo and standard-surface-base-albedo: three layers, the coat over a dielectric interface over a
// Lambertian; the base interface's lobe as each model has it (models/builtin/09-openpbr.glsl, 11-standard-surface.glsl)
void base_albedo_tables(const StackGpu& sg, uint32_t sets, std::vector<float>& t) {
    const CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    if (sets & STACK_TABLES_OPENPBR_BASE) {
        interface_albedo(openpbr_specular_eta(p), openpbr_roughened_alpha(p, false), STACK_TABLE_OPENPBR_BASE, t);
        interface_albedo(openpbr_specular_eta(p), openpbr_roughened_alpha(p, true), STACK_TABLE_OPENPBR_BASE_PR261, t);
    }
    if (sets & STACK_TABLES_STANDARD_SURFACE_BASE)
        interface_albedo(p.eta * p.base_eta, layer_alpha(sg.layers[1]), STACK_TABLE_STANDARD_SURFACE_BASE, t);
    if (sets & STACK_TABLES_OPENPBR_SEPARABLE)
        interface_albedo(openpbr_specular_eta(p), openpbr_roughened_alpha(p, false), STACK_TABLE_OPENPBR_SEPARABLE_BASE,
                         t, FGD_SEPARABLE);
}

// The sets of the coat's albedo: E_coat with G2 (coat-albedo) and with the separable G (openpbr-separable's first)
void coat_albedo_sets(const StackGpu& sg, uint32_t sets, std::vector<float>& t) {
    if (sets & STACK_TABLES_COAT_ALBEDO) {
        const std::vector<float> e = coat_albedo_table(sg);
        std::copy(e.begin(), e.end(), t.begin() + STACK_TABLE_COAT_ALBEDO);
    }
    if (sets & STACK_TABLES_OPENPBR_SEPARABLE)
        interface_albedo(layer_eta(sg.layers[0]), layer_alpha(sg.layers[0]), STACK_TABLE_OPENPBR_SEPARABLE_COAT, t,
                         FGD_SEPARABLE);
}

}   // namespace

float interfaced_internal_reflectance(float eta) {
    const double r_e = cosine_average([&](float mu) { return double(fresnel_dielectric(mu, eta)); });
    return float(1.0 - (1.0 - r_e) / (double(eta) * eta));
}

float interfaced_body_node(float eta, float alpha, uint32_t i, uint32_t j, uint32_t k, uint32_t n_az, uint32_t n_cap) {
    const float mi = interfaced_mu_node(i), mj = interfaced_mu_node(j), phi = interfaced_phi_node(k);
    const vec3 a(std::sqrt(1.0f - mi * mi), 0.0f, mi);
    const float sj = std::sqrt(1.0f - mj * mj);
    const vec3 b(sj * std::cos(phi), sj * std::sin(phi), mj);
    // the visible normals of the more grazing direction (node i <= j: a)
    return float(i <= j ? interfaced_body_quadrature(a, b, eta, alpha, n_az, n_cap)
                        : interfaced_body_quadrature(b, a, eta, alpha, n_az, n_cap));
}

// Adobe's tables at its nodes (adobe_ior_node, roughness j / 31, adobe_mu_node): what impl/data/*.h tabulate, the
// complements 1 - E kept in [0, 1] as the published unorm16 values are (the quadrature's 1e-5 above 1 at j = 1)
float adobe_opaque_dielectric_complement(uint i, uint j, uint k) {
    const float r = float(j) / 31.0f;
    return std::max(0.0f, 1.0f - sums_at(adobe_ior_node(i), r * r, adobe_mu_node(k), FGD_SEPARABLE).fgd.x);
}
float adobe_opaque_dielectric_average_complement(uint i, uint j) {
    const float r = float(j) / 31.0f, eta = adobe_ior_node(i);
    return float(std::max(
        0.0, 1.0 - cosine_average([&](float mu) { return double(sums_at(eta, r * r, mu, FGD_SEPARABLE).fgd.x); })));
}
float adobe_ideal_metal_complement(uint j, uint k) {
    const float r = float(j) / 31.0f;
    return std::max(0.0f, 1.0f - sums_at(1.5f, r * r, adobe_mu_node(k), FGD_SEPARABLE).lobe);
}
float adobe_ideal_metal_average_complement(uint j) {
    const float r = float(j) / 31.0f;
    return float(std::max(
        0.0, 1.0 - cosine_average([&](float mu) { return double(sums_at(1.5f, r * r, mu, FGD_SEPARABLE).lobe); })));
}

// Cycles' tables at its nodes (cycles_table_node): what src/scene/shader.tables holds
float cycles_ggx_e(uint i, uint j) {
    const float r = cycles_table_node(i, CYCLES_E_NODES, 1.0f);
    return sums_at(1.5f, r * r, cycles_table_node(j, CYCLES_E_NODES, 1.0f), FGD_G2).lobe;
}
float cycles_ggx_e_avg(uint i) {
    const float r = cycles_table_node(i, CYCLES_E_NODES, 1.0f);
    return float(cosine_average([&](float mu) { return double(sums_at(1.5f, r * r, mu, FGD_G2).lobe); }));
}
float cycles_schlick_ior_s(uint i, uint j, uint k) {
    // the mean over the visible normals of l of s(l.m) = saturate((F(l.m, ior) - F0) / (1 - F0)), 0 where
    // v = reflect(l, m) is below the horizon (fgd_quadrature's visible-normal mode with the remapped Fresnel)
    const float r = cycles_table_node(i, CYCLES_S_NODES, 1.0f), z = cycles_table_node(k, CYCLES_S_NODES, 0.99f);
    const float ior = (1.0f + z * z) / (1.0f - z * z);
    return sums_at(ior, r * r, cycles_table_node(j, CYCLES_S_NODES, 1.0f), FGD_VISIBLE_NORMALS | FGD_FRESNEL_REMAPPED)
        .fgd.x;
}

std::vector<float> stack_tables(const StackGpu& sg, uint32_t sets) {
    std::vector<float> t(STACK_TABLE_FLOATS, 0.0f);
    const uint32_t layers = stack_layer_count(sg.info);
    const bool three_layer_dielectric_base = layers == 3 && layer_kind(sg.layers[0]) == KIND_DIELECTRIC &&
                                             layer_kind(sg.layers[1]) == KIND_DIELECTRIC &&
                                             layer_kind(sg.layers[2]) == KIND_LAMBERTIAN;
    if (three_layer_dielectric_base) {   // the coat's albedo and the base interface's, as each model has it
        coat_albedo_sets(sg, sets, t);
        base_albedo_tables(sg, sets, t);
        return t;
    }
    const bool two_layer_opaque = layers == 2 && layer_kind(sg.layers[1]) != KIND_DIELECTRIC;
    if (!two_layer_opaque) return t;
    coat_albedo_sets(sg, sets, t);
    if (sets & STACK_TABLES_ADOBE) adobe_tables(sg, t);
    if (sets & STACK_TABLES_CYCLES) cycles_tables(sg, t);
    if (sets & STACK_TABLES_INTERFACED) interfaced_tables(sg, t);
    return t;
}

}   // namespace gonio
