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
#include "fgd_quadrature.glsl"
#include "../kernel_interface.glsl"

const uint TABLE_FGD_STRIDE = TABLE_NMU * TABLE_NALPHA * 3u;
const uint TABLE_TIR_OFFSET = MAX_LAYERS * TABLE_FGD_STRIDE;
const uint TABLE_SET_FLOATS = TABLE_TIR_OFFSET + MAX_LAYERS * TABLE_NMU * TABLE_NALPHA;   // one convention's set
const uint TABLE_SETS = 2u;                         // set 0 (separable G) then set 1 (height-correlated G2)
const uint TABLE_FLOATS = TABLE_SETS * TABLE_SET_FLOATS;
// One entry of interface `layer`'s tables (set 1: g2, height-correlated G2; set 0: separable G1(l) G1(v)) by
// gonio's one half-vector quadrature of a rough interface's albedo (models/fgd_quadrature.glsl, which the
// albedo-scaling model's coat albedo also calls), FGD_NODES_THETA x FGD_NODES_PHI nodes.
// xyz: FGD per channel; w: TIR transmitted fraction.
GONIO_INLINE vec4 belcour_table_entry(LayerGpu L, float mu, float alpha, bool g2) {
    return fgd_quadrature(L, mu, alpha, g2, FGD_NODES_THETA, FGD_NODES_PHI);
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
