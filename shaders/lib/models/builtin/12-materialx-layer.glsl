// gonio-model: materialx-layer
// citation: MaterialX pbrlib `layer` of a `dielectric_bsdf` over the base, as its GLSL generator computes it
//   (AcademySoftwareFoundation/MaterialX @4177b2cb: libraries/pbrlib/genglsl/mx_layer_bsdf.glsl, mx_dielectric_bsdf.glsl,
//   mx_conductor_bsdf.glsl, mx_oren_nayar_diffuse_bsdf.glsl, lib/mx_microfacet_specular.glsl at its default
//   DIRECTIONAL_ALBEDO_METHOD 0)
// summary: top + (1 - E_mx(v) comp) base: the coat's GGX lobe with Turquin's compensation comp = 1 + F_avg (1 - E_ss)
//   / E_ss, its directional albedo E_mx from MaterialX's rational fit, the base (a conductor also compensated)
//   passed that throughput, seen from v; no refraction, the coat IOR leaves the base alone
// stacks: one colourless dielectric coat over a Lambertian or conductor base
// mapping: layer(top = dielectric_bsdf(weight 1, tint 1, ior = n_coat / n_exterior, roughness = alpha_coat (pbrlib's
//   roughness is GGX alpha), scatter_mode R), base = oren_nayar_diffuse_bsdf(color = albedo A, roughness 0) or
//   conductor_bsdf(ior = n, extinction = k of the conductor relative to the exterior, roughness = alpha_base))
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - E_mx(v) comp(v), seen from v, not from l; E_mx is a fit, and the
//   compensated lobes add energy)
// plan: coat
// refuses: scattering-medium = {id} has no scattering medium ({layer}): the layer of two BSDFs has no medium
// refuses: absorbing-medium = {id}: a layer of two BSDFs has no medium between them ({layer} absorbs): a
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
// M_FLOAT_EPS, alpha to [M_FLOAT_EPS, 1], as the code does. f here is response / n.l.
#ifndef GONIO_MODEL_MATERIALX_LAYER_GLSL
#define GONIO_MODEL_MATERIALX_LAYER_GLSL
#include "models/common.glsl"

const float MX_FLOAT_EPS = 1e-8f;   // M_FLOAT_EPS of MaterialX's GLSL (libraries/stdlib/genglsl/lib/mx_math.glsl)

// mx_ggx_dir_albedo_analytic's (A, B): the GGX directional albedo is F0 A + F90 B (MaterialX's rational fit)
GONIO_INLINE vec2 mx_ggx_dir_albedo_ab(float mu, float alpha) {
    const float x = mu, y = alpha, x2 = x * x, y2 = y * y;
    const vec4 r = vec4(0.1003f, 0.9345f, 1.0f, 1.0f) + vec4(-0.6303f, -2.323f, -1.765f, 0.2281f) * x +
                   vec4(9.748f, 2.229f, 8.263f, 15.94f) * y + vec4(-2.038f, -3.748f, 11.53f, -55.83f) * x * y +
                   vec4(29.34f, 1.424f, 28.96f, 13.08f) * x2 + vec4(-8.245f, -0.7684f, -7.507f, 41.26f) * y2 +
                   vec4(-26.44f, 1.436f, -36.11f, 54.9f) * x2 * y + vec4(19.99f, 0.2913f, 15.86f, 300.2f) * x * y2 +
                   vec4(-5.448f, 0.6286f, 33.37f, -285.1f) * x2 * y2;
    return clamp(vec2(r.x / r.z, r.y / r.w), vec2(0.0f), vec2(1.0f));
}

// mx_ggx_energy_compensation: 1 + F_avg (1 - E_ss) / E_ss, F_avg = F0 + (1 - F0) / 21
GONIO_INLINE vec3 mx_ggx_energy_compensation(float mu, float alpha, vec3 f0) {
    const vec2 ab = mx_ggx_dir_albedo_ab(mu, alpha);
    const float e_ss = ab.x + ab.y;
    const vec3 f_avg = f0 + (vec3(1.0f) - f0) * (1.0f / 21.0f);
    return vec3(1.0f) + f_avg * ((1.0f - e_ss) / e_ss);
}

// The microfacet part D G / (4 n.l n.v) of mx_dielectric_bsdf's and mx_conductor_bsdf's responses over n.l, with
// their clamps (a GGX of alpha in [M_FLOAT_EPS, 1], isotropic)
GONIO_INLINE float mx_ggx_lobe(vec3 l, vec3 v, float alpha_in) {
    const float alpha = clamp(alpha_in, MX_FLOAT_EPS, 1.0f), a2 = alpha * alpha;
    const float nl = clamp(l.z, MX_FLOAT_EPS, 1.0f), nv = clamp(v.z, MX_FLOAT_EPS, 1.0f);
    const vec3 h = normalize(l + v);
    const float lambda_l = sqrt(a2 + (1.0f - a2) * nl * nl), lambda_v = sqrt(a2 + (1.0f - a2) * nv * nv);
    const float g = 2.0f * nl * nv / (lambda_l * nv + lambda_v * nl);   // mx_ggx_smith_G2
    return ggx_D(h, alpha) * g / (4.0f * nv * nl);
}

// The coat's F0, mx_ior_to_f0, and the top's throughput 1 - mx_ggx_dir_albedo(n.v, alpha, F0, 1) comp
GONIO_INLINE float mx_dielectric_f0(float eta) { return ((eta - 1.0f) / (eta + 1.0f)) * ((eta - 1.0f) / (eta + 1.0f)); }
GONIO_INLINE float mx_dielectric_throughput(float mu_v, float alpha_in, float eta) {
    const float alpha = clamp(alpha_in, MX_FLOAT_EPS, 1.0f), nv = clamp(mu_v, MX_FLOAT_EPS, 1.0f);
    const float f0 = mx_dielectric_f0(eta);
    const vec2 ab = mx_ggx_dir_albedo_ab(nv, alpha);
    return 1.0f - (f0 * ab.x + ab.y) * mx_ggx_energy_compensation(nv, alpha, vec3(f0)).x;
}

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
#endif
