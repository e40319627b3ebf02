// models/production.glsl: what several production models compute alike: the F82-tint metal (Kutz et al. 2021, "Novel
// aspects of the Adobe Standard Material"; OpenPBR "Metal", adobe/openpbr-bsdf, Cycles' Principled BSDF), the
// metal's F0 and tint for a conductor base, and Kulla & Conty's fit of the average dielectric Fresnel.
#ifndef GONIO_MODELS_PRODUCTION_GLSL
#define GONIO_MODELS_PRODUCTION_GLSL
#include "models/common.glsl"

// F82-tint: F(mu) = F_S(mu) - mu (1 - mu)^6 / (mu_b (1 - mu_b)^6) (F_S(mu_b) - tint F_S(mu_b)), mu_b = 1/7,
// F_S(mu) = F0 + (1 - F0) (1 - mu)^5, i.e. F_S(mu) - b mu (1 - mu)^6 with b = F_S(mu_b) (1 - tint) / (mu_b (1 - mu_b)^6)
// (mu clamped to 1: rounding takes |l.h| above it at h = l, and GLSL's pow of the negative 1 - mu is undefined). Not
// clamped to [0, 1]: OpenPBR's specification does not; Adobe's and Cycles' codes saturate it (f82_tint_saturated)
GONIO_INLINE vec3 f82_tint(vec3 f0, vec3 tint, float mu_in) {
    const float mu_b = 1.0f / 7.0f, mu = min(mu_in, 1.0f);
    const float x = 1.0f - mu, xb = 1.0f - mu_b;
    const float x5 = x * x * x * x * x, xb5 = xb * xb * xb * xb * xb;
    const vec3 fs = f0 + (vec3(1.0f) - f0) * x5;
    const vec3 fs_b = f0 + (vec3(1.0f) - f0) * xb5;
    const float w = mu * x5 * x / (mu_b * xb5 * xb);
    return fs - w * (fs_b - tint * fs_b);
}
GONIO_INLINE vec3 f82_tint_saturated(vec3 f0, vec3 tint, float mu) {
    return clamp(f82_tint(f0, tint, mu), vec3(0.0f), vec3(1.0f));
}
// Its cosine-weighted hemispherical average 2 int_0^1 F(mu) mu dmu = F0 + (1 - F0) / 21 - b / 126 (Cycles bsdf_util.h
// fresnel_f82_Fss; adobe/openpbr-bsdf's avgF82 saturates it)
GONIO_INLINE vec3 f82_tint_average(vec3 f0, vec3 tint) {
    const float mu_b = 1.0f / 7.0f, xb = 1.0f - mu_b;
    const float xb5 = xb * xb * xb * xb * xb;
    const vec3 b = (f0 + (vec3(1.0f) - f0) * xb5) * (vec3(1.0f) - tint) / (mu_b * xb5 * xb);
    return f0 + (vec3(1.0f) - f0) / 21.0f - b / 126.0f;
}

// A conductor base as a production model's metal: F0 its normal-incidence reflectance and the F82 tint
// min(1, F(1/7) / F_S(1/7)) of its exact Fresnel F, n and k relative to the exterior (a metal's colour as an artist
// measures it in air: F82-tint gives no complex IOR for a coat to change)
GONIO_INLINE vec3 metal_f0(CoatParams p) { return conductor_normal_reflectance(p.base_c0 * p.eta, p.base_c1 * p.eta); }
GONIO_INLINE vec3 metal_f82_tint(CoatParams p, vec3 f0) {
    const float mu_b = 1.0f / 7.0f, xb = 1.0f - mu_b;
    const vec3 fs_b = f0 + (vec3(1.0f) - f0) * (xb * xb * xb * xb * xb);
    return min(vec3(1.0f), fresnel_conductor(mu_b, p.base_c0 * p.eta, p.base_c1 * p.eta) / fs_b);
}

// A coat's transmittance along a direction of cosine mu^t inside it, exp(-tau / mu^t) per channel, with tau the
// optical depth of one crossing at normal incidence (a tint t^(1 / mu^t), t = exp(-tau), as pow computes it: 1 for a
// channel that does not absorb, 0 at mu^t = 0 for one that does)
GONIO_INLINE vec3 coat_transmittance(vec3 tau, float mu_t) {
    vec3 t;
    for (int c = 0; c < 3; ++c) t[c] = tau[c] > 0.0f ? (mu_t > 0.0f ? exp(-tau[c] / mu_t) : 0.0f) : 1.0f;
    return t;
}

// Kulla & Conty 2017's fit of the average dielectric Fresnel 2 int_0^1 F(mu, eta) mu dmu ("Revisiting Physically
// Based Shading at Imageworks", slide 18), as adobe/openpbr-bsdf (openpbr_average_fresnel) and Cycles
// (fresnel_dielectric_Fss) write it: one branch above 1, one below; at eta = 1 exactly Adobe's code takes the one below
// (0.00267), Cycles' the one above (0)
GONIO_INLINE float kulla_conty_average_fresnel_above_1(float eta) { return (eta - 1.0f) / (4.08567f + 1.00071f * eta); }
GONIO_INLINE float kulla_conty_average_fresnel_below_1(float eta) {
    return 0.997118f + eta * (0.1014f - eta * (0.965241f + eta * 0.130607f));
}
#endif
