// gonio-model: gltf-sheen
// citation: glTF 2.0 KHR_materials_sheen (ratified) over the metal-rough material's diffuse, as the extension
//   computes it (KhronosGroup/glTF @60ad0f83 extensions/2.0/Khronos/KHR_materials_sheen/README.md: "Sheen BTDF"
//   (alpha_g = sheenRoughness^2, sheen_distribution, sheen_visibility, lambda_sheen), "Albedo-scaling technique")
// family: sheen
// summary: sheenColor D(h; sheenRoughness^2) G2 / (4 mu_l mu_v) over min(1 - max(sheenColor) E(mu_v),
//   1 - max(sheenColor) E(mu_l)) baseColor / pi: Estevez & Kulla's sheen at the squared roughness, the base scaled
//   by the white lobe's albedo from both directions
// stacks: a fibre layer (an index-matched smooth interface over an SGGX fibre medium of optical depth 1) over a
//   Lambertian
// mapping: sheenRoughnessFactor = the fibres' fibre_roughness (the number OpenPBR's fuzz_roughness carries; glTF
//   squares it into the distribution's alpha), sheenColorFactor = the fibres' scattering albedo, baseColorFactor =
//   the Lambertian's albedo with metallicFactor 0 and KHR_materials_specular's specularFactor 0 (no dielectric lobe)
// artist-parameters: fibres-over-lambertian = sheenRoughnessFactor, sheenColorFactor (colour), baseColorFactor
//   (colour)
// represents: fibres-over-lambertian
// reciprocal: yes
// energy-conserving: no (the lobe's albedo is not the slab's, and max(sheenColor) E may exceed the light the lobe
//   takes)
// table: gltf-sheen-albedo 129
// tables: gltf-sheen-albedo
// refuses: fibre-depth-not-1 = {id} is set beside the sheen authors' unit slab (optical depth 1), whose alpha and
//   colour its mapping reads; this fibre layer's optical depth is {optical_depth}
//
// models/builtin/18-gltf-sheen.glsl: `gltf-sheen`. The extension's sheen BRDF is Estevez & Kulla's (models/sheen.glsl
// charlie_lobe: the distribution and the fitted Lambda, without the paper's terminator softening, as the extension
// writes it) at alpha_g = sheenRoughness^2, and the material under it is scaled by
//   sheen_albedo_scaling = min(1 - max3(sheenColor) E(VdotN), 1 - max3(sheenColor) E(LdotN)),
// E the white sheen BRDF's directional albedo, which the extension leaves to a lookup table; gonio integrates it for
// the stack (this file's `gltf-sheen-albedo` set, on the host, models/sheen.glsl sheen_albedo_quadrature), the scaling
// at least 0 (sheen_albedo_scaling: at alpha_g 0.01 the lobe's albedo is 1.29 at mu 0.035). It is
// `charlie-sheen` with the roughness squared: the mapping carries the fibre layer's alpha into sheenRoughness as an
// artist porting OpenPBR's fuzz_roughness would.
#ifndef GONIO_MODEL_GLTF_SHEEN_GLSL
#define GONIO_MODEL_GLTF_SHEEN_GLSL
#include "models/sheen.glsl"

// The set this file declares (`table: gltf-sheen-albedo`): E(mu) at GLTF_SHEEN_ALBEDO_NODES nodes mu = i / 128
const uint GLTF_SHEEN_ALBEDO_NODES = 129u;
#ifdef __cplusplus
static_assert(GLTF_SHEEN_ALBEDO_NODES == STACK_TABLE_GLTF_SHEEN_ALBEDO_FLOATS, "the set's `table:` size");
#endif

// alpha_g = sheenRoughness^2
GONIO_INLINE float gltf_sheen_alpha(LayerGpu fibres) {
    const float r = layer_microflake_alpha(fibres);
    return r * r;
}

GONIO_INLINE vec3 model_gltf_sheen(CoatParams p, uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    const LayerGpu fibres = model_layer(0u);
    return charlie_over_lambertian(layer_scattering_albedo(fibres), gltf_sheen_alpha(fibres), p.base_c0, STACK_TABLE_GLTF_SHEEN_ALBEDO,
                                   GLTF_SHEEN_ALBEDO_NODES, terms, l, v);
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void gltf_sheen_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, layer_microflake_alpha(model_layer(0u)));    // sheenRoughnessFactor
    artist_value(a, layer_scattering_albedo(model_layer(0u)));   // sheenColorFactor
    artist_value(a, p.base_c0);                                  // baseColorFactor
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) gltf_sheen_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// gltf-sheen-albedo on the host: E(mu) of the white lobe at alpha_g by gonio's quadrature (models/sheen.glsl)
GONIO_INLINE void gltf_sheen_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_GLTF_SHEEN_ALBEDO) == 0u || table_stack_shape(s) != TABLE_SHAPE_TWO_LAYER_OPAQUE) return;
    const float alpha = gltf_sheen_alpha(s.layers[0]);
    if (alpha <= 0.0f) return;   // not a fibre layer: no model that reads the set takes the stack
    sheen_store_albedo(STACK_TABLE_GLTF_SHEEN_ALBEDO, GLTF_SHEEN_ALBEDO_NODES, SHEEN_LOBE_CHARLIE, alpha);
}
#define GONIO_MODEL_TABLES(s, sets) gltf_sheen_tables(s, sets)
#endif
#endif
