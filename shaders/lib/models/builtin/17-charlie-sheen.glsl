// gonio-model: charlie-sheen
// citation: Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF" (Sony Pictures Imageworks), its
//   distribution and fitted Lambda as KHR_materials_sheen writes them (KhronosGroup/glTF @60ad0f83
//   extensions/2.0/Khronos/KHR_materials_sheen/README.md: sheen_distribution, sheen_visibility, lambda_sheen, and the
//   albedo-scaling layering); the Lambda's five coefficient pairs as Imageworks' own code has them
//   (AcademySoftwareFoundation/OpenShadingLanguage @3985c0fa src/libbsdl/include/BSDL/MTX/bsdf_sheen_impl.h)
// family: sheen
// summary: C D(h) G2 / (4 mu_l mu_v) over min(1 - max(C) E(mu_l), 1 - max(C) E(mu_v)) f_base: the "Charlie"
//   distribution (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi), the authors' fitted Lambda in
//   G2 = 1 / (1 + Lambda(mu_l) + Lambda(mu_v)), the base scaled by the white lobe's albedo E from both directions
// stacks: a fibre layer (an index-matched smooth interface over an SGGX fibre medium of optical depth 1) over a
//   Lambertian
// mapping: the lobe's alpha = the fibres' fibre_roughness (the distribution's own alpha, not squared: glTF squares
//   its sheenRoughness into it), sheen colour C = the fibres' scattering albedo, base colour = the Lambertian's albedo
// artist-parameters: fibres-over-lambertian = alpha, sheen_color (colour), base_color (colour)
// represents: fibres-over-lambertian
// reciprocal: yes
// energy-conserving: no (the lobe's albedo is not the slab's, and max(C) E may exceed the light the lobe takes)
// table: charlie-albedo 129
// tables: charlie-albedo
// refuses: fibre-depth-not-1 = {id} is set beside the sheen authors' unit slab (optical depth 1), whose alpha and
//   colour its mapping reads; this fibre layer's optical depth is {optical_depth}
//
// models/builtin/17-charlie-sheen.glsl: `charlie-sheen`, the sheen of glTF, Standard Surface, Filament and
// MaterialX's default `sheen_bsdf`. Estevez & Kulla's distribution of microfibres' normals,
//   D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi),
// with their fitted Lambda (the paper's section 3, table 1: five coefficients interpolated in (1 - alpha)^2 between
// the alpha = 0 and alpha = 1 sets),
//   L(x) = a / (1 + b x^c) + d x + e,   Lambda(mu) = exp(L(mu)) for mu < 0.5, exp(2 L(0.5) - L(1 - mu)) above,
//   f_sheen = C D(h) / ((1 + Lambda(mu_l) + Lambda(mu_v)) 4 mu_l mu_v)
// (KHR_materials_sheen's sheen_visibility; the paper's terminator softening of Lambda(mu_l), eq. 4, is a shading
// trick for light on a mesh, not part of the BRDF the spec and pbrt's baseline compute). Layered as
// KHR_materials_sheen layers it: f = f_sheen + min(1 - max(C) E(mu_v), 1 - max(C) E(mu_l)) f_base, E(mu) the white
// lobe's directional albedo, gonio's own quadrature of it per stack (this file's `charlie-albedo` set, on the host;
// the spec's E table is a lookup of the same integral), the scaling at least 0 (models/sheen.glsl
// sheen_albedo_scaling: the lobe's albedo exceeds 1 at low alpha and grazing).
#ifndef GONIO_MODEL_CHARLIE_SHEEN_GLSL
#define GONIO_MODEL_CHARLIE_SHEEN_GLSL
#include "models/sheen.glsl"

// The set this file declares (`table: charlie-albedo`): E(mu) at CHARLIE_ALBEDO_NODES nodes mu = i / 128
const uint CHARLIE_ALBEDO_NODES = 129u;
#ifdef __cplusplus
static_assert(CHARLIE_ALBEDO_NODES == STACK_TABLE_CHARLIE_ALBEDO_FLOATS, "the set's `table:` size");
#endif

GONIO_INLINE vec3 model_charlie_sheen(CoatParams p, uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    const LayerGpu fibres = model_layer(0u);
    return charlie_over_lambertian(layer_scattering_albedo(fibres), layer_microflake_alpha(fibres), p.base_c0, STACK_TABLE_CHARLIE_ALBEDO,
                                   CHARLIE_ALBEDO_NODES, terms, l, v);
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void charlie_sheen_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, layer_microflake_alpha(model_layer(0u)));    // alpha
    artist_value(a, layer_scattering_albedo(model_layer(0u)));   // sheen_color
    artist_value(a, p.base_c0);                                  // base_color
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) charlie_sheen_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// charlie-albedo on the host: E(mu) of the white lobe by gonio's quadrature (models/sheen.glsl)
GONIO_INLINE void charlie_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_CHARLIE_ALBEDO) == 0u || table_stack_shape(s) != TABLE_SHAPE_TWO_LAYER_OPAQUE) return;
    const float alpha = layer_microflake_alpha(s.layers[0]);
    if (alpha <= 0.0f) return;   // not a fibre layer: no model that reads the set takes the stack
    sheen_store_albedo(STACK_TABLE_CHARLIE_ALBEDO, CHARLIE_ALBEDO_NODES, SHEEN_LOBE_CHARLIE, alpha);
}
#define GONIO_MODEL_TABLES(s, sets) charlie_tables(s, sets)
#endif
#endif
