// models/sheen.glsl: the sheen lobes the sheen models share (models/builtin/16- to 21-*sheen*.glsl): Estevez & Kulla's
// "Charlie" distribution with its fitted Lambda or with Neubelt's visibility, and a linearly transformed cosine
// (Heitz et al. 2016) as Zeltner, Burley & Chiang 2022 orient it about the view direction. Each model file names the
// code it follows; this file only writes the formulas once. On the host, a lobe's directional albedo by gonio's
// quadrature, for the files' E tables.
#ifndef GONIO_MODELS_SHEEN_GLSL
#define GONIO_MODELS_SHEEN_GLSL
#include "common.glsl"

// D(h), Estevez & Kulla 2017 eq. 2: (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi)
GONIO_INLINE float charlie_D(vec3 h, float alpha) {
    const float sin2 = max(1.0f - h.z * h.z, 0.0f);
    return (2.0f + 1.0f / alpha) * pow(sin2, 0.5f / alpha) / (2.0f * PI);
}

// Their fitted L(x) (section 3, table 1), the alpha = 1 and alpha = 0 sets mixed by (1 - alpha)^2 (KHR_materials_sheen
// l(x, alpha_g); Imageworks' BSDL bsdf_sheen_impl.h)
GONIO_INLINE float charlie_L(float x, float alpha) {
    const float t = (1.0f - alpha) * (1.0f - alpha);
    const float a = mix(21.5473f, 25.3245f, t), b = mix(3.82987f, 3.32435f, t), c = mix(0.19823f, 0.16801f, t);
    const float d = mix(-1.97760f, -1.27393f, t), e = mix(-4.32054f, -4.85967f, t);
    return a / (1.0f + b * pow(x, c)) + d * x + e;
}

// Lambda(mu) = exp(L(mu)) below 0.5, exp(2 L(0.5) - L(1 - mu)) above
GONIO_INLINE float charlie_lambda(float mu, float alpha) {
    return mu < 0.5f ? exp(charlie_L(mu, alpha)) : exp(2.0f * charlie_L(0.5f, alpha) - charlie_L(1.0f - mu, alpha));
}

// The white Charlie lobe with the fitted Lambda, D / ((1 + Lambda(mu_l) + Lambda(mu_v)) 4 mu_l mu_v), l and v above
GONIO_INLINE float charlie_lobe(vec3 l, vec3 v, float alpha) {
    return charlie_D(normalize(l + v), alpha) /
           ((1.0f + charlie_lambda(l.z, alpha) + charlie_lambda(v.z, alpha)) * 4.0f * l.z * v.z);
}

// The white Charlie lobe with Neubelt & Pettineo 2013's smooth denominator, D / (4 (mu_l + mu_v - mu_l mu_v))
GONIO_INLINE float charlie_neubelt_lobe(vec3 l, vec3 v, float alpha) {
    return charlie_D(normalize(l + v), alpha) / (4.0f * (l.z + v.z - l.z * v.z));
}

// KHR_materials_sheen's albedo scaling of the layers under the sheen, min(1 - c E(mu_v), 1 - c E(mu_l)), c the sheen
// colour's largest channel, at least 0: the Charlie lobe with the fitted Lambda has an albedo above 1 at low alpha
// and grazing (1.29 at mu 0.035 for alpha 0.01, gonio's quadrature), where the unclamped scaling would make the base
// reflect negative light; the extension scales the base "to avoid energy gain", its E table (Enterprise PBR's) stays
// below 1, and gonio scores no negative BRDF
GONIO_INLINE float sheen_albedo_scaling(float c, float e_l, float e_v) {
    return max(min(1.0f - c * e_v, 1.0f - c * e_l), 0.0f);
}

// The Charlie lobe with the fitted Lambda at alpha, tinted C, over a Lambertian of albedo `base` scaled as
// KHR_materials_sheen scales it, E read from `nodes` values at mu = i / (nodes - 1) from e_offset (charlie-sheen,
// gltf-sheen); TERM_TOP the lobe, TERM_BASE the base
GONIO_INLINE vec3 charlie_over_lambertian(vec3 colour, float alpha, vec3 base, uint e_offset, uint nodes, uint terms,
                                          vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += colour * charlie_lobe(l, v, alpha);
    if ((terms & TERM_BASE) != 0u) {
        const float c = max(colour.x, max(colour.y, colour.z));
        f += base / PI *
             sheen_albedo_scaling(c, model_stack_table_at(e_offset, nodes, l.z), model_stack_table_at(e_offset, nodes, v.z));
    }
    return f;
}

// A linearly transformed cosine in the frame of the view direction, M^-1 = [[a_inv, 0, b_inv], [0, a_inv, 0],
// [0, 0, 1]]: its density at l, the cosine-weighted lobe f mu_l of unit albedo, D_o(w / |w|) a_inv^2 / |w|^3 with
// w = M^-1 l', D_o(w) = max(w.z, 0) / pi, l' the light in the frame whose x axis is v's azimuth
GONIO_INLINE float sheen_ltc_density(vec3 l, vec3 v, float a_inv, float b_inv) {
    const float s = length(vec2(v.x, v.y));
    const vec2 c = s > 0.0f ? vec2(v.x, v.y) / s : vec2(1.0f, 0.0f);
    const vec3 lv = vec3(c.x * l.x + c.y * l.y, c.x * l.y - c.y * l.x, l.z);   // l about z by -phi(v)
    const vec3 w = vec3(a_inv * lv.x + b_inv * lv.z, a_inv * lv.y, lv.z);
    const float len = length(w);
    if (len <= 0.0f) return 0.0f;
    return max(w.z / len, 0.0f) / PI * a_inv * a_inv / (len * len * len);
}

// The set zeltner22-sheen declares (`table: zeltner22-ltc`), which cycles-sheen reads too: the sheen authors' a_inv,
// b_inv and R at the stack's alpha, each at their table's ZELTNER22_MU_NODES nodes mu_v = i / (ZELTNER22_MU_NODES - 1)
const uint ZELTNER22_MU_NODES = 32u;
const uint STACK_TABLE_ZELTNER22_A_INV = STACK_TABLE_ZELTNER22_LTC;
const uint STACK_TABLE_ZELTNER22_B_INV = STACK_TABLE_ZELTNER22_A_INV + ZELTNER22_MU_NODES;
const uint STACK_TABLE_ZELTNER22_R = STACK_TABLE_ZELTNER22_B_INV + ZELTNER22_MU_NODES;

// Their slab's reflectance R(mu_v) at the stack's alpha, read linearly along mu_v from that set
GONIO_INLINE float zeltner22_table_reflectance(float mu_v) {
    return model_stack_table_at(STACK_TABLE_ZELTNER22_R, ZELTNER22_MU_NODES, mu_v);
}
// Their white lobe R(mu_v) LTC(l) / mu_l, r = zeltner22_table_reflectance(v.z), l and v above
GONIO_INLINE float zeltner22_table_lobe(vec3 l, vec3 v, float r) {
    const float a_inv = model_stack_table_at(STACK_TABLE_ZELTNER22_A_INV, ZELTNER22_MU_NODES, v.z);
    const float b_inv = model_stack_table_at(STACK_TABLE_ZELTNER22_B_INV, ZELTNER22_MU_NODES, v.z);
    return r * sheen_ltc_density(l, v, a_inv, b_inv) / l.z;
}

#ifdef __cplusplus
// A white lobe's directional albedo E(mu) = the integral of f(l, v) mu_v over the hemisphere of v, l at mu: Gauss-
// Legendre in mu_v (SHEEN_ALBEDO_MU_NODES) and the midpoint rule in the azimuth over [0, pi] (the lobes are even in
// it; SHEEN_ALBEDO_PHI_NODES). The lobes: SHEEN_LOBE_CHARLIE (the fitted Lambda), SHEEN_LOBE_NEUBELT
const uint SHEEN_LOBE_CHARLIE = 0u, SHEEN_LOBE_NEUBELT = 1u;
const uint SHEEN_ALBEDO_MU_NODES = 96u;
const uint SHEEN_ALBEDO_PHI_NODES = 96u;
GONIO_INLINE double sheen_albedo_quadrature(uint lobe, float mu, float alpha, uint n_mu, uint n_phi) {
    const vec3 l = vec3(sqrt(1.0f - mu * mu), 0.0f, mu);
    double sum = 0.0;
    for (uint j = 0u; j < n_mu; ++j) {
        const float mv = float(table_gauss_legendre_node(n_mu, j)), sv = sqrt(1.0f - mv * mv);
        double row = 0.0;
        for (uint k = 0u; k < n_phi; ++k) {
            const float phi = (float(k) + 0.5f) * PI / float(n_phi);
            const vec3 v = vec3(sv * cos(phi), sv * sin(phi), mv);
            row += (lobe == SHEEN_LOBE_CHARLIE ? charlie_lobe(l, v, alpha) : charlie_neubelt_lobe(l, v, alpha)) * mv;
        }
        sum += table_gauss_legendre_weight(n_mu, j) * row * 2.0 * double(PI) / double(n_phi);
    }
    return sum;
}
// E at `nodes` nodes mu = i / (nodes - 1) (node 0 at SHEEN_ALBEDO_MU_MIN: the lobes need mu > 0) into elements offset..
const float SHEEN_ALBEDO_MU_MIN = 1e-4f;
GONIO_INLINE void sheen_store_albedo(uint offset, uint nodes, uint lobe, float alpha) {
    for (uint i = 0u; i < nodes; ++i) {
        const float mu = max(float(i) / float(nodes - 1u), SHEEN_ALBEDO_MU_MIN);
        model_stack_table_store(offset + i, float(sheen_albedo_quadrature(lobe, mu, alpha, SHEEN_ALBEDO_MU_NODES,
                                                                          SHEEN_ALBEDO_PHI_NODES)));
    }
}
#endif
#endif
