// models/materialx.glsl: MaterialX pbrlib's GLSL microfacet pieces, transcribed from AcademySoftwareFoundation/MaterialX
// @4177b2cb libraries/pbrlib/genglsl/lib/mx_microfacet_specular.glsl, mx_microfacet.glsl (DIRECTIONAL_ALBEDO_METHOD 0),
// for the models that compute as MaterialX's graphs do (materialx-layer, openpbr+materialx): its rational fit to the
// GGX directional albedo, Turquin's energy compensation, its dielectric_bsdf's throughput and the microfacet term of
// its responses, with the code's clamps (n.v, n.l, v.h at least M_FLOAT_EPS, alpha in [M_FLOAT_EPS, 1]).
#ifndef GONIO_MODELS_MATERIALX_GLSL
#define GONIO_MODELS_MATERIALX_GLSL
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

// mx_fresnel_hoffman_schlick with exponent 5 and F90 = 1: Schlick's F0 + (1 - F0)(1 - mu)^5 less Hoffman's F82 term,
// a (1 - F82 tint) at mu = 1/7 (generalized_schlick_bsdf's color0, color82, color90 = 1)
GONIO_INLINE vec3 mx_fresnel_f82(float mu_in, vec3 f0, vec3 f82) {
    const float cos_max = 1.0f / 7.0f, xm = 1.0f - cos_max;
    const float factor = 1.0f / (cos_max * xm * xm * xm * xm * xm * xm);
    const float x = clamp(mu_in, 0.0f, 1.0f), y = 1.0f - x, y5 = y * y * y * y * y;
    const vec3 a = mix(f0, vec3(1.0f), xm * xm * xm * xm * xm) * (vec3(1.0f) - f82) * factor;
    return mix(f0, vec3(1.0f), y5) - a * x * y5 * y;
}
GONIO_INLINE float mx_dielectric_throughput(float mu_v, float alpha_in, float eta) {
    const float alpha = clamp(alpha_in, MX_FLOAT_EPS, 1.0f), nv = clamp(mu_v, MX_FLOAT_EPS, 1.0f);
    const float f0 = mx_dielectric_f0(eta);
    const vec2 ab = mx_ggx_dir_albedo_ab(nv, alpha);
    return 1.0f - (f0 * ab.x + ab.y) * mx_ggx_energy_compensation(nv, alpha, vec3(f0)).x;
}
#endif
