// models/belcour_tables.glsl: the FGD and TIR tables of Belcour 2018 (section 5 and supplemental), computed
// by gonio for the interfaces of the stack at hand, on the device (shaders/tables.comp) or on the CPU twin.
//
// FGD(mu, alpha; eta, k) is the directional albedo of one rough interface's reflection, Fresnel included:
//   FGD = integral over the upper hemisphere of F(l.h) D(h) G(l, v) / (4 l.z v.z) v.z dv,   l.z = mu,
// with the reference's GGX D and exact Fresnel (dielectric, TIR included, or conductor). Two sets of tables, one
// per masking-shadowing convention (docs/MODELS.md, "Conventions"):
//   set 0: separable Smith G = G1(l) G1(v), what the official codes tabulate (Belcour's tables as Photon-v2's port
//          and TMbLM-Rendering's tm_TIR.bin / tm_GD.bin hold them; Mitsuba 0.6 MicrofacetDistribution::G), the
//          models' default;
//   set 1: the reference's height-correlated G2 = 1 / (1 + Lambda(l) + Lambda(v)), for the `+g2` variants.
// A model reads the set of its convention (model_convention() & CONVENTION_G2).
// TIR(mu, alpha; eta_c) is Belcour's convention: the fraction of light crossing interface i from its denser
// side that is transmitted, 1 - (the share of a GGX reflection lobe of roughness alpha, F = 1, that lands outside
// the escape cone sin(theta) < eta_c), eta_c = min(eta, 1 / eta) (1: index-matched, nothing trapped). Belcour
// uses it on the way up (interfaces with eta > 1), the transfer-matrix model on whichever way is denser-first.
// Randrianandrasana et al. 2021's tm_TIR.bin tabulates that share (research notes, models.md section 1.9).
//
// Tables are tabulated only on the slice the stack needs: per interface j, its own (eta, k), on the grid of
// TABLE_NMU x TABLE_NALPHA nodes (table_node_mu, table_node_alpha: kernel_interface.glsl, which the host shares),
// read back with bilinear interpolation between nodes. Layout, in floats:
//   FGD of interface j: [j][a][c][rgb] at j * TABLE_FGD_STRIDE;  TIR of interface j: TABLE_TIR_OFFSET + [j][a][c],
// within each set; set 1 starts at TABLE_SET_FLOATS.
// The includer provides float model_table(uint index) and uint model_convention().
#ifndef GONIO_BELCOUR_TABLES_GLSL
#define GONIO_BELCOUR_TABLES_GLSL
#include "common.glsl"
#include "../kernel_interface.glsl"

const uint TABLE_FGD_STRIDE = TABLE_NMU * TABLE_NALPHA * 3u;
const uint TABLE_TIR_OFFSET = MAX_LAYERS * TABLE_FGD_STRIDE;
const uint TABLE_SET_FLOATS = TABLE_TIR_OFFSET + MAX_LAYERS * TABLE_NMU * TABLE_NALPHA;   // one convention's set
const uint TABLE_SETS = 2u;                         // set 0 (separable G) then set 1 (height-correlated G2)
const uint TABLE_FLOATS = TABLE_SETS * TABLE_SET_FLOATS;
// The models' conventions (bits of model_convention(); 0: what the official codes compute).
const uint CONVENTION_G2 = 1u;                 // height-correlated Smith G2 in the GGX lobes and the tables
const uint CONVENTION_TIR_BELOW_MEDIA = 2u;    // Belcour's TIR term kept below an absorbing medium
const uint TABLE_NODES_THETA = 256u;   // half-vector quadrature per table entry: theta_m nodes
const uint TABLE_NODES_PHI = 64u;      // and phi_m nodes over [0, pi] (the integrand is symmetric about the plane of l)

// One entry of interface `layer`'s tables by quadrature in half-vector space (v = reflect(l, m),
// f cos_v dv = F D G2 (l.m) / l.z dm), with tan(theta_m) = alpha (e^(L u) - 1), L = ln(tan(theta_max) / alpha + 1),
// u uniform: nodes far finer than alpha near the peak and even steps in log tan theta_m in the tail, up to
// theta_max = (90 degrees + theta_l) / 2, beyond which v = reflect(l, m) is below the horizon for every phi_m
// (nodes there would be wasted: the Fresnel step at the critical angle needs them). A stratified
// visible-normal grid converged as 1/N here (3e-3 off at 64 x 64 nodes, measured).
// g2: height-correlated G2 (set 1), else separable G1(l) G1(v) (set 0).
// xyz: FGD per channel; w: TIR transmitted fraction.
GONIO_INLINE vec4 belcour_table_entry(LayerGpu L, float mu, float alpha, bool g2) {
    uint kind = layer_kind(L);
    // a conductor or a dielectric; no table for another kind (the models that read tables refuse it): NaN
    if (kind != KIND_CONDUCTOR && kind != KIND_DIELECTRIC) return vec4(model_nan());
    float a = max(alpha, MODEL_MIN_ALPHA);
    float c = max(mu, 1e-4f);
    vec3 l = vec3(sqrt(max(0.0f, 1.0f - c * c)), 0.0f, c);
    float eta = layer_eta(L);
    float eta_c = kind == KIND_DIELECTRIC ? min(eta, 1.0f / eta) : 2.0f;   // crossing from the denser side
    vec3 cond_eta = layer_conductor_eta(L), cond_k = layer_conductor_k(L);
    float theta_max = min(0.5f * (0.5f * PI + acos(c)), 1.5706f);
    float log_range = log(tan(theta_max) / a + 1.0f);
    vec3 fgd = vec3(0.0f);
    float lobe = 0.0f, outside = 0.0f;
    float dphi = PI / float(TABLE_NODES_PHI);
    // phi_m by rotation: one sin/cos pair per entry
    float cd = cos(dphi), sd = sin(dphi);
    for (uint i = 0u; i < TABLE_NODES_THETA; ++i) {
        float u = (float(i) + 0.5f) / float(TABLE_NODES_THETA);
        float e = exp(log_range * u);
        float tan_m = a * (e - 1.0f);
        float cos_m = 1.0f / sqrt(1.0f + tan_m * tan_m), sin_m = tan_m * cos_m;
        float dtheta = a * log_range * e * cos_m * cos_m;   // d theta_m / du
        float d = ggx_D(vec3(sin_m, 0.0f, cos_m), a) * sin_m * dtheta;
        float cp = cos(0.5f * dphi), sp = sin(0.5f * dphi);
        for (uint j = 0u; j < TABLE_NODES_PHI; ++j) {
            vec3 m = vec3(sin_m * cp, sin_m * sp, cos_m);
            float lm = dot(l, m);
            vec3 v = reflect_about(l, m);
            float cn = cp * cd - sp * sd;
            sp = sp * cd + cp * sd;
            cp = cn;
            if (lm <= 0.0f || v.z <= 0.0f) continue;
            float w = d * (g2 ? ggx_G2(l, v, a) : ggx_G2_separable(l, v, a)) * lm;
            if (kind == KIND_CONDUCTOR) fgd += w * fresnel_conductor(lm, cond_eta, cond_k);
            else if (kind == KIND_DIELECTRIC) fgd += vec3(w * fresnel_dielectric(lm, eta));
            lobe += w;
            if (1.0f - v.z * v.z > eta_c * eta_c) outside += w;
        }
    }
    float norm = 2.0f * dphi / (float(TABLE_NODES_THETA) * c);   // both halves of phi, du, 1 / l.z
    float tir = (eta_c >= 1.0f || !(lobe > 0.0f)) ? 1.0f : 1.0f - outside / lobe;
    return vec4(fgd.x * norm, fgd.y * norm, fgd.z * norm, tir);
}

// Bilinear lookup between the nodes: fractional indices of (mu, alpha).
GONIO_INLINE vec2 table_coords(float mu, float alpha) {
    float x = sqrt(clamp(mu, 0.0f, 1.0f)) * float(TABLE_NMU - 1u);
    float y = sqrt(clamp(alpha, 0.0f, 1.0f)) * float(TABLE_NALPHA - 1u);
    return vec2(x, y);
}

// The first float of the table set the model's convention reads.
GONIO_INLINE uint table_set_offset() { return (model_convention() & CONVENTION_G2) != 0u ? TABLE_SET_FLOATS : 0u; }

GONIO_INLINE vec3 model_fgd(uint layer, float mu, float alpha) {
    vec2 t = table_coords(mu, alpha);
    uint set = table_set_offset();
    uint c0 = min(uint(t.x), TABLE_NMU - 2u), a0 = min(uint(t.y), TABLE_NALPHA - 2u);
    float fx = t.x - float(c0), fy = t.y - float(a0);
    vec3 r = vec3(0.0f);
    for (uint k = 0u; k < 4u; ++k) {
        uint dc = k & 1u, da = k >> 1u;
        float w = (dc == 1u ? fx : 1.0f - fx) * (da == 1u ? fy : 1.0f - fy);
        uint base = set + layer * TABLE_FGD_STRIDE + ((a0 + da) * TABLE_NMU + c0 + dc) * 3u;
        r += w * vec3(model_table(base), model_table(base + 1u), model_table(base + 2u));
    }
    return r;
}

GONIO_INLINE float model_tir(uint layer, float mu, float alpha) {
    vec2 t = table_coords(mu, alpha);
    uint set = table_set_offset();
    uint c0 = min(uint(t.x), TABLE_NMU - 2u), a0 = min(uint(t.y), TABLE_NALPHA - 2u);
    float fx = t.x - float(c0), fy = t.y - float(a0);
    float r = 0.0f;
    for (uint k = 0u; k < 4u; ++k) {
        uint dc = k & 1u, da = k >> 1u;
        float w = (dc == 1u ? fx : 1.0f - fx) * (da == 1u ? fy : 1.0f - fy);
        r += w *
             model_table(set + TABLE_TIR_OFFSET + layer * TABLE_NMU * TABLE_NALPHA + (a0 + da) * TABLE_NMU + c0 + dc);
    }
    return r;
}
#endif
