// gonio-model: materialx-layer
// citation: MaterialX pbrlib `layer` of a `dielectric_bsdf` over the base, as its GLSL generator computes it
//   (AcademySoftwareFoundation/MaterialX @4177b2cb: libraries/pbrlib/genglsl/mx_layer_bsdf.glsl, mx_dielectric_bsdf.glsl,
//   mx_conductor_bsdf.glsl, mx_oren_nayar_diffuse_bsdf.glsl, lib/mx_microfacet_specular.glsl at its default
//   DIRECTIONAL_ALBEDO_METHOD 0)
// family: production
// summary: top + (1 - E_mx(v) comp) base: the coat's GGX lobe with Turquin's compensation comp = 1 + F_avg (1 - E_ss)
//   / E_ss, its directional albedo E_mx from MaterialX's rational fit, the base (a conductor also compensated)
//   passed that throughput, seen from v; no refraction, the coat IOR leaves the base alone
// stacks: one colourless dielectric coat over a Lambertian or conductor base
// mapping: layer(top = dielectric_bsdf(weight 1, tint 1, ior = n_coat / n_exterior, roughness = alpha_coat (pbrlib's
//   roughness is GGX alpha), scatter_mode R), base = oren_nayar_diffuse_bsdf(color = albedo A, roughness 0) or
//   conductor_bsdf(ior = n, extinction = k of the conductor relative to the exterior, roughness = alpha_base))
// artist-parameters: coat-over-lambertian = dielectric_bsdf.weight, dielectric_bsdf.tint (colour),
//   dielectric_bsdf.ior, dielectric_bsdf.roughness, oren_nayar_diffuse_bsdf.color (colour),
//   oren_nayar_diffuse_bsdf.roughness
// artist-parameters: coat-over-conductor = dielectric_bsdf.weight, dielectric_bsdf.tint (colour), dielectric_bsdf.ior,
//   dielectric_bsdf.roughness, conductor_bsdf.ior (colour), conductor_bsdf.extinction (colour),
//   conductor_bsdf.roughness
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - E_mx(v) comp(v), seen from v, not from l; E_mx is a fit, and the
//   compensated lobes add energy)
// plan: coat
// refuses: scattering-medium = {id} has no scattering medium ({layer}): the layer of two BSDFs has no medium
// refuses: absorbing-medium = {id}: a layer of two BSDFs has no medium between them ({layer}): a
//   dielectric_bsdf's tint colours its own reflection, not the light through it
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian base (oren_nayar_diffuse_bsdf of roughness 0)
//   or a conductor (conductor_bsdf), not a {base}
// refuses: not-two-layers = {id} is one dielectric_bsdf layered over one base here; this stack has {layers} layers
//
// models/builtin/12-materialx-layer.glsl: `materialx-layer`, MaterialX's layering as its GLSL code computes it:
//   mx_layer_bsdf: response = top.response + base.response top.throughput
//   mx_dielectric_bsdf (reflection): response = D F(v.h) G comp / (4 n.v) (n.l, the cosine, cancelled), F the exact
//     dielectric Fresnel of ior, D GGX, G height-correlated (mx_ggx_smith_G2), comp = 1 + F_avg (1 - E_ss) / E_ss
//     (mx_ggx_energy_compensation, Turquin 2019 eq. 14, 16) with F_avg = F0 + (1 - F0) / 21 (mx_fresnel_average) and
//     E_ss = mx_ggx_dir_albedo(n.v, alpha, 1, 1); throughput = 1 - mx_ggx_dir_albedo(n.v, alpha, F0, 1) comp
//   mx_conductor_bsdf: D F_conductor(v.h) G comp / (4 n.v), comp of F_avg from its F0 = F_conductor(1)
//   mx_oren_nayar_diffuse_bsdf at roughness 0: color / pi (A = 1, B = 0)
// mx_ggx_dir_albedo(mu, alpha, F0, F90) = F0 A + F90 B, (A, B) = clamp(r.xy / r.zw, 0, 1) from the rational fit
// mx_ggx_dir_albedo_analytic (a fit to Monte Carlo data of the GGX albedo); n.v, n.l, v.h clamped to at least
// M_FLOAT_EPS, alpha to [M_FLOAT_EPS, 1], as the code does (models/materialx.glsl). f here is response / n.l.
#ifndef GONIO_MODEL_MATERIALX_LAYER_GLSL
#define GONIO_MODEL_MATERIALX_LAYER_GLSL
#include "models/common.glsl"
#include "models/materialx.glsl"

GONIO_INLINE vec3 model_materialx_layer(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    const float nv = clamp(v.z, MX_FLOAT_EPS, 1.0f);
    if ((terms & TERM_TOP) != 0u) {
        const float vh = clamp(dot(v, normalize(l + v)), MX_FLOAT_EPS, 1.0f);
        const float comp = mx_ggx_energy_compensation(nv, clamp(p.alpha0, MX_FLOAT_EPS, 1.0f),
                                                      vec3(mx_dielectric_f0(p.eta))).x;
        f += vec3(fresnel_dielectric(vh, p.eta) * mx_ggx_lobe(l, v, p.alpha0) * comp);
    }
    if ((terms & TERM_BASE) == 0u) return f;
    vec3 base;
    if (p.base_kind == KIND_LAMBERTIAN) {
        base = p.base_c0 * INV_PI;
    } else if (p.base_kind == KIND_CONDUCTOR) {
        // the conductor in the exterior (the layer has no refraction): its n, k relative to the coat times eta
        const vec3 n = p.base_c0 * p.eta, k = p.base_c1 * p.eta;
        const float vh = clamp(dot(v, normalize(l + v)), MX_FLOAT_EPS, 1.0f);
        const vec3 comp = mx_ggx_energy_compensation(nv, clamp(p.alpha1, MX_FLOAT_EPS, 1.0f),
                                                     fresnel_conductor(1.0f, n, k));
        base = fresnel_conductor(vh, n, k) * comp * mx_ggx_lobe(l, v, p.alpha1);
    } else {
        return vec3(model_nan());
    }
    return f + mx_dielectric_throughput(v.z, p.alpha0, p.eta) * base;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order): pbrlib's roughness is GGX alpha
GONIO_INLINE void materialx_layer_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);         // dielectric_bsdf.weight
    artist_value(a, vec3(1.0f));   // dielectric_bsdf.tint
    artist_value(a, p.eta);        // dielectric_bsdf.ior
    artist_value(a, p.alpha0);     // dielectric_bsdf.roughness
    if (p.base_kind == KIND_CONDUCTOR) {
        artist_value(a, p.base_c0 * p.eta);   // conductor_bsdf.ior, relative to the exterior
        artist_value(a, p.base_c1 * p.eta);   // conductor_bsdf.extinction
        artist_value(a, p.alpha1);            // conductor_bsdf.roughness
    } else {
        artist_value(a, p.base_c0);   // oren_nayar_diffuse_bsdf.color
        artist_value(a, 0.0f);        // oren_nayar_diffuse_bsdf.roughness
    }
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) materialx_layer_artist_parameters(p, diffuse, a)
#endif
