// gonio-model: materialx-sheen
// citation: MaterialX pbrlib `layer` of a `sheen_bsdf` in mode `zeltner` over the base, as its GLSL generator computes
//   it (AcademySoftwareFoundation/MaterialX @4177b2cb: libraries/pbrlib/genglsl/mx_sheen_bsdf.glsl,
//   lib/mx_microfacet_sheen.glsl mx_zeltner_sheen_brdf, mx_zeltner_sheen_dir_albedo, mx_zeltner_sheen_ltc_aInv,
//   mx_zeltner_sheen_ltc_bInv; mx_layer_bsdf.glsl): OpenPBR v1.1's fuzz in its reference graph
//   (AcademySoftwareFoundation/OpenPBR reference/open_pbr_surface.mtlx: sheen_bsdf mode "zeltner", roughness =
//   fuzz_roughness, inside layer(top = fuzz, base = the coated base))
// family: sheen
// summary: E(mu_v, r) color LTC(l) / mu_l over (1 - E(mu_v, r)) base: Zeltner, Burley & Chiang's LTC sheen with
//   closed-form fits (a Gaussian in mu_v for E, rationals for a_inv and b_inv) in place of their table
// stacks: a fibre layer (an index-matched smooth interface over an SGGX fibre medium of optical depth 1) over a
//   Lambertian
// mapping: sheen_bsdf(weight 1, color = the fibres' scattering albedo, roughness = the fibres' fibre_roughness (OpenPBR
//   fuzz_roughness, the LTC table's alpha), mode zeltner) layered over oren_nayar_diffuse_bsdf(color = the
//   Lambertian's albedo, roughness 0)
// artist-parameters: fibres-over-lambertian = sheen_bsdf.roughness, sheen_bsdf.color (colour),
//   oren_nayar_diffuse_bsdf.color (colour)
// represents: fibres-over-lambertian
// reciprocal: no
// energy-conserving: no (the fitted E is not the LTC's own albedo, and the base is scaled by 1 - E seen from v only)
// refuses: fibre-depth-not-1 = {id} is fitted to the sheen authors' unit slab (optical depth 1: density 1 x thickness
//   1); this fibre layer's optical depth is {optical_depth}
//
// models/builtin/19-materialx-sheen.glsl: `materialx-sheen`, OpenPBR's fuzz as its reference MaterialX graph computes
// it. mx_sheen_bsdf in mode 1 (zeltner), roughness clamped to [0.01, 1] (y), x = n.v:
//   response = E(x, y) color D_ltc(l) weight, throughput = 1 - E(x, y) weight,
//   E = exp(-((x - m) / s)^2 / 2) / (s sqrt(2 pi)) + o   (s, m, o rationals in y: mx_zeltner_sheen_dir_albedo),
//   D_ltc = D_o(w) (a_inv / |w|^2)^2, w = M^-1 l' (mx_zeltner_sheen_brdf; a_inv, b_inv the rationals in x and y of
//   mx_zeltner_sheen_ltc_aInv / _bInv; l' in the frame whose x axis is v's component along the surface), the same
//   linearly transformed cosine as zeltner22-sheen's (models/sheen.glsl sheen_ltc_density); the response carries
//   the cosine, so f = response / mu_l. mx_layer_bsdf: f = top + throughput base, weight 1. The fits' credits
//   (Stephen Hill, in OSL's comments) and their distance from the authors' table are docs/MODELS.md's.
#ifndef GONIO_MODEL_MATERIALX_SHEEN_GLSL
#define GONIO_MODEL_MATERIALX_SHEEN_GLSL
#include "models/materialx.glsl"
#include "models/sheen.glsl"

// mx_zeltner_sheen_dir_albedo(x, y)
GONIO_INLINE float materialx_zeltner_albedo(float x, float y) {
    const float s = y * (0.0206607f + 1.58491f * y) / (0.0379424f + y * (1.32227f + y));
    const float m = y * (-0.193854f + y * (-1.14885f + y * (1.7932f - 0.95943f * y * y))) / (0.046391f + y);
    const float o = y * (0.000654023f + (-0.0207818f + 0.119681f * y) * y) / (1.26264f + y * (-1.92021f + y));
    const float z = (x - m) / s;
    return exp(-0.5f * z * z) / (s * sqrt(2.0f * PI)) + o;
}
// mx_zeltner_sheen_ltc_aInv(x, y), mx_zeltner_sheen_ltc_bInv(x, y)
GONIO_INLINE float materialx_zeltner_a_inv(float x, float y) {
    return (2.58126f * x + 0.813703f * y) * y / (1.0f + 0.310327f * x * x + 2.60994f * x * y);
}
GONIO_INLINE float materialx_zeltner_b_inv(float x, float y) {
    return sqrt(1.0f - x) * (y - 1.0f) * y * y * y / (0.0000254053f + 1.71228f * x - 1.71506f * x * y + 1.34174f * y * y);
}

GONIO_INLINE vec3 model_materialx_sheen(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    const LayerGpu fibres = model_layer(0u);
    const float x = clamp(v.z, MX_FLOAT_EPS, 1.0f), y = clamp(layer_microflake_alpha(fibres), 0.01f, 1.0f);
    // the fit dips below 0 (-2.1e-5 at roughness 0.1, n.v 0.79): at least 0 here, as mode 0's E is clamped, so that no
    // bin is negative (gonio scores no negative BRDF)
    const float e = max(materialx_zeltner_albedo(x, y), 0.0f);
    if ((terms & TERM_TOP) != 0u)
        f += layer_scattering_albedo(fibres) *
             (e * sheen_ltc_density(l, v, materialx_zeltner_a_inv(x, y), materialx_zeltner_b_inv(x, y)) / l.z);
    if ((terms & TERM_BASE) != 0u) f += p.base_c0 / PI * (1.0f - e);
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void materialx_sheen_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, layer_microflake_alpha(model_layer(0u)));    // sheen_bsdf.roughness
    artist_value(a, layer_scattering_albedo(model_layer(0u)));   // sheen_bsdf.color
    artist_value(a, p.base_c0);                                  // oren_nayar_diffuse_bsdf.color
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) materialx_sheen_artist_parameters(p, diffuse, a)
#endif
