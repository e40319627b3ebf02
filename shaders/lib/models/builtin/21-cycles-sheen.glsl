// gonio-model: cycles-sheen
// citation: Blender Cycles' Principled BSDF sheen (Blender 4.0 and later) over its diffuse, as its closure code
//   computes it (blender/cycles v5.0.0: src/kernel/svm/closure.h (the Principled's sheen: sheen_weight, sheen_tint,
//   sheen_roughness, closure_layering_weight), closure/bsdf_sheen.h (bsdf_sheen_setup, bsdf_sheen_eval: the LTC and
//   its albedo from scene/shader.tables table_sheen_ltc, the sheen authors' `volume` table)
// family: sheen
// summary: tint R(mu_v, r) LTC(l) / mu_l over saturate(1 - max(tint) R(mu_v, r)) base: Zeltner, Burley & Chiang's LTC
//   read from their table, the layers below scaled by the tinted sheen's albedo seen from v
// stacks: a fibre layer (an index-matched smooth interface over an SGGX fibre medium of optical depth 1) over a
//   Lambertian
// mapping: Sheen Weight 1, Sheen Tint = the fibres' scattering albedo, Sheen Roughness = the fibres' fibre_roughness
//   (the table's alpha, unsquared), Base Color = the Lambertian's albedo, Metallic 0, Roughness 0 (Lambertian
//   diffuse), Specular IOR Level 0 (no specular closure), Coat Weight 0
// artist-parameters: fibres-over-lambertian = Sheen Roughness, Sheen Tint (colour), Base Color (colour)
// represents: fibres-over-lambertian
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - max(tint) R(mu_v), seen from v only)
// tables: zeltner22-ltc
// refuses: fibre-depth-not-1 = {id} is fitted to the sheen authors' unit slab (optical depth 1: density 1 x thickness
//   1); this fibre layer's optical depth is {optical_depth}
//
// models/builtin/21-cycles-sheen.glsl: `cycles-sheen`. bsdf_sheen_setup clamps the roughness to [1e-3, 1] and reads
// (a_inv, b_inv, R) bilinearly at (cos N.I, roughness) from table_sheen_ltc, nodes i / 31 (lookup_table_read_2D): the
// sheen authors' `volume` table (the per-stack set zeltner22-ltc reads it as their code does; the array in
// models/zeltner22_ltc_table.glsl); it multiplies the closure's weight by R and evaluates the LTC's density
// (1 / pi) localO.z (a / |w|^2)^2 in the frame of I, the view; the closure's weight is the sheen's tint (weight 1).
// closure_layering_weight then scales the layers below (the diffuse) by saturate(1 - reduce_max(tint R)). This is
// zeltner22-sheen with the layering tinted by max(tint).
#ifndef GONIO_MODEL_CYCLES_SHEEN_GLSL
#define GONIO_MODEL_CYCLES_SHEEN_GLSL
#include "models/sheen.glsl"

GONIO_INLINE vec3 model_cycles_sheen(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    const vec3 tint = layer_scattering_albedo(model_layer(0u));
    const float r = zeltner22_table_reflectance(v.z);
    if ((terms & TERM_TOP) != 0u) f += tint * zeltner22_table_lobe(l, v, r);
    if ((terms & TERM_BASE) != 0u)
        f += p.base_c0 / PI * clamp(1.0f - max(tint.x, max(tint.y, tint.z)) * r, 0.0f, 1.0f);
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void cycles_sheen_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, layer_microflake_alpha(model_layer(0u)));    // Sheen Roughness
    artist_value(a, layer_scattering_albedo(model_layer(0u)));   // Sheen Tint
    artist_value(a, p.base_c0);                                  // Base Color
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) cycles_sheen_artist_parameters(p, diffuse, a)
#endif
