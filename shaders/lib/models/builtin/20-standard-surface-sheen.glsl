// gonio-model: standard-surface-sheen
// citation: Autodesk Standard Surface's sheen (Autodesk/standard-surface index.html @34b1d5bd, "Sheen") as its MaterialX
//   graph computes it (AcademySoftwareFoundation/MaterialX @4177b2cb libraries/bxdf/standard_surface.mtlx: sheen_bsdf
//   (weight = sheen, color = sheen_color, roughness = sheen_roughness) layered over the diffuse;
//   libraries/pbrlib/genglsl/mx_sheen_bsdf.glsl mode 0 (conty_kulla), lib/mx_microfacet_sheen.glsl
//   mx_imageworks_sheen_brdf, mx_imageworks_sheen_dir_albedo at DIRECTIONAL_ALBEDO_METHOD 0), MaterialX's default
//   sheen
// family: sheen
// summary: color D(h; r) / (4 (mu_l + mu_v - mu_l mu_v)) over (1 - E(mu_v, r)) base: Estevez & Kulla's distribution
//   with Neubelt's smooth denominator for their Lambda, its albedo MaterialX's rational fit, seen from v
// stacks: a fibre layer (an index-matched smooth interface over an SGGX fibre medium of optical depth 1) over a
//   Lambertian
// mapping: sheen 1, sheen_color = the fibres' scattering albedo, sheen_roughness = the fibres' fibre_roughness (the
//   graph passes it to sheen_bsdf unsquared), base 1, base_color = the Lambertian's albedo, diffuse_roughness 0,
//   specular 0
// artist-parameters: fibres-over-lambertian = sheen_roughness, sheen_color (colour), base_color (colour)
// represents: fibres-over-lambertian
// reciprocal: no
// energy-conserving: no (the fitted E is not the lobe's own albedo, and the base is scaled by 1 - E seen from v only)
// refuses: fibre-depth-not-1 = {id} is set beside the sheen authors' unit slab (optical depth 1), whose alpha and
//   colour its mapping reads; this fibre layer's optical depth is {optical_depth}
//
// models/builtin/20-standard-surface-sheen.glsl: `standard-surface-sheen`. mx_sheen_bsdf in mode 0:
//   response = color D(n.h; r) / (4 (n.l + n.v - n.l n.v)) n.l weight,   throughput = 1 - E(n.v, r) weight,
//   D = (2 + 1/r) sin(theta_h)^(1/r) / (2 pi), 1/r = 1 / max(r, 0.005) (mx_imageworks_sheen_NDF),
//   E = clamp(p(n.v, r) / q(n.v, r), 0, 1), p and q quadratics in (n.v, r) (mx_imageworks_sheen_dir_albedo_analytic),
// n.l, n.v and n.h clamped to at least M_FLOAT_EPS; mx_layer_bsdf: f = top + throughput base, weight (sheen) 1.
#ifndef GONIO_MODEL_STANDARD_SURFACE_SHEEN_GLSL
#define GONIO_MODEL_STANDARD_SURFACE_SHEEN_GLSL
#include "models/materialx.glsl"
#include "models/sheen.glsl"

// mx_imageworks_sheen_dir_albedo_analytic(x, r), clamped to [0, 1] as mx_imageworks_sheen_dir_albedo clamps it
GONIO_INLINE float materialx_imageworks_sheen_albedo(float x, float r) {
    const vec2 q = vec2(13.67300f, 1.0f) + vec2(-68.78018f, 61.57746f) * x + vec2(799.08825f, 442.78211f) * r +
                   vec2(-905.00061f, 2597.49308f) * x * r + vec2(60.28956f, 121.81241f) * x * x +
                   vec2(1086.96473f, 3045.55075f) * r * r;
    return clamp(q.x / q.y, 0.0f, 1.0f);
}

GONIO_INLINE vec3 model_standard_surface_sheen(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    const LayerGpu fibres = model_layer(0u);
    const float r = layer_microflake_alpha(fibres), nv = clamp(v.z, MX_FLOAT_EPS, 1.0f);
    if ((terms & TERM_TOP) != 0u) {
        const float nl = clamp(l.z, MX_FLOAT_EPS, 1.0f), nh = clamp(normalize(l + v).z, MX_FLOAT_EPS, 1.0f);
        const float d = charlie_D(vec3(0.0f, 0.0f, nh), max(r, 0.005f));
        f += layer_scattering_albedo(fibres) * (d / (4.0f * (nl + nv - nl * nv)));
    }
    if ((terms & TERM_BASE) != 0u) f += p.base_c0 / PI * (1.0f - materialx_imageworks_sheen_albedo(nv, r));
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void standard_surface_sheen_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, layer_microflake_alpha(model_layer(0u)));    // sheen_roughness
    artist_value(a, layer_scattering_albedo(model_layer(0u)));   // sheen_color
    artist_value(a, p.base_c0);                                  // base_color
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) standard_surface_sheen_artist_parameters(p, diffuse, a)
#endif
