// gonio-model: zeltner22-sheen
// citation: Zeltner, Burley & Chiang 2022, "Practical Multiple-Scattering Sheen Using Linearly Transformed Cosines"
//   (SIGGRAPH Talks), as its authors' public code computes it (tizian/ltc-sheen @92624114:
//   pbrt-v3/src/materials/sheenltc.cpp, the `volume` table), layered as OpenPBR v1.1 layers its fuzz
//   (AcademySoftwareFoundation/OpenPBR @f8d6d947 index.html, "Fuzz": F f_fuzz + (1 - F E_fuzz) f_base, fuzz_weight F 1)
// family: sheen
// summary: C R(mu_v, alpha) LTC(l) / mu_l over (1 - R(mu_v, alpha)) f_base: the authors' linearly transformed cosine
//   fitted to their SGGX fibre slab, its reflectance R from the same table, the base scaled by one minus the white
//   lobe's albedo seen from v
// stacks: a fibre layer (an index-matched smooth interface over an SGGX fibre medium of optical depth 1) over a
//   Lambertian
// mapping: fuzz_roughness = alpha (the fibres' fibre_roughness; the table's own alpha, sigma = alpha^2), fuzz_color =
//   the fibres' scattering albedo, fuzz_weight = 1, base_color = the Lambertian's albedo
// artist-parameters: fibres-over-lambertian = fuzz_roughness, fuzz_color (colour), base_color (colour)
// represents: fibres-over-lambertian
// reciprocal: no
// energy-conserving: no (the LTC integrates to R exactly, but the base is scaled by 1 - R(mu_v), seen from v only)
// table: zeltner22-ltc 96
// tables: zeltner22-ltc
// refuses: fibre-depth-not-1 = {id} is fitted to the authors' unit slab (optical depth 1: density 1 x thickness 1);
//   this fibre layer's optical depth is {optical_depth}
//
// models/builtin/16-zeltner22-sheen.glsl: `zeltner22-sheen`. The authors fitted, per (mu_v, alpha) on their 32 x 32
// grid, a linearly transformed cosine (Heitz et al. 2016) to the BRDF of a unit slab of SGGX fibres (Heitz et al.
// 2015; gonio's `phase = "sggx-fibre"`, stacks/sheen/ltc-sheen-slab.toml), of albedo 1, at most 16 scattering events:
//   f(l, v) mu_l = C R(mu_v, alpha) D_o(w / |w|) a_inv^2 / |w|^3,   w = M^-1 l',   M^-1 = [[a_inv, 0, b_inv],
//   [0, a_inv, 0], [0, 0, 1]],   D_o(w) = max(w.z, 0) / pi,
// l' the light in the frame whose x axis is v's azimuth (sheenltc.cpp rotateVector(wi, z, -phi(wo)): pbrt's wo is
// the view v, its wi the light l), (a_inv, b_inv, R) bilinear in (alpha, mu_v) over the table's nodes j / 31, i / 31
// (fetchCoeffs). R is the slab's directional reflectance, so the lobe's albedo is C R. The fuzz over the rest as
// OpenPBR layers it with fuzz_weight 1: f = f_fuzz + (1 - E_fuzz(mu_v)) f_base, E_fuzz = R, untinted (OpenPBR:
// E of the fuzz lobe with its colour set to white). The colour scales the lobe linearly: the slab's multiple
// scattering in a coloured medium is what the reference walks and the model does not.
// The table: data/sheen/ltc-sheen-volume-ltc.csv (tools/ltc_sheen/ltc_table.py writes it and the host array,
// models/zeltner22_ltc_table.glsl); this file's set holds its row at the stack's alpha, interpolated on the host.
#ifndef GONIO_MODEL_ZELTNER22_SHEEN_GLSL
#define GONIO_MODEL_ZELTNER22_SHEEN_GLSL
#include "models/sheen.glsl"
#include "models/zeltner22_ltc_table.glsl"

#ifdef __cplusplus
static_assert(3u * ZELTNER22_MU_NODES == STACK_TABLE_ZELTNER22_LTC_FLOATS, "the set's `table:` size");
static_assert(ZELTNER22_MU_NODES == ZELTNER22_LTC_NODES, "the authors' table's nodes");
#endif

GONIO_INLINE vec3 model_zeltner22_sheen(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    const float r = zeltner22_table_reflectance(v.z);
    if ((terms & TERM_TOP) != 0u) f += layer_scattering_albedo(model_layer(0u)) * zeltner22_table_lobe(l, v, r);
    if ((terms & TERM_BASE) != 0u) f += p.base_c0 / PI * (1.0f - r);
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void zeltner22_sheen_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, layer_microflake_alpha(model_layer(0u)));    // fuzz_roughness
    artist_value(a, layer_scattering_albedo(model_layer(0u)));   // fuzz_color
    artist_value(a, p.base_c0);                                  // base_color
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) zeltner22_sheen_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// zeltner22-ltc on the host: the authors' table's two rows about the stack's alpha, blended as sheenltc.cpp's
// fetchCoeffs blends them (row = clamp(alpha, 0, 1 - eps) x 31), at each of its nodes of mu_v; the shader's linear
// reading in mu_v then completes its bilinear lookup
GONIO_INLINE void zeltner22_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_ZELTNER22_LTC) == 0u || table_stack_shape(s) != TABLE_SHAPE_TWO_LAYER_OPAQUE) return;
    const float row = clamp(layer_microflake_alpha(s.layers[0]), 0.0f, 1.0f - 1e-7f) * float(ZELTNER22_LTC_NODES - 1u);
    const uint j = min(uint(row), ZELTNER22_LTC_NODES - 2u);
    const float t = row - float(j);
    for (uint i = 0u; i < ZELTNER22_MU_NODES; ++i)
        for (uint k = 0u; k < 3u; ++k)
            model_stack_table_store(STACK_TABLE_ZELTNER22_LTC + k * ZELTNER22_MU_NODES + i,
                                    ZELTNER22_LTC_TABLE[j][i][k] * (1.0f - t) + ZELTNER22_LTC_TABLE[j + 1u][i][k] * t);
}
#define GONIO_MODEL_TABLES(s, sets) zeltner22_tables(s, sets)
#endif
#endif
