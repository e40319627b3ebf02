// ggx.glsl: the isotropic GGX (Trowbridge-Reitz) microfacet distribution, height-correlated Smith
// masking-shadowing, and visible-normal sampling. All directions in the local frame of the interface:
// z is the macro-normal, pointing to the side the light arrives from.
#ifndef GONIO_GGX_GLSL
#define GONIO_GGX_GLSL
#include "compat.glsl"

// D(m) (Walter et al. 2007, eq. 33), written as 1/(pi a^2 (mx^2/a^2 + my^2/a^2 + mz^2)^2) so that small
// alpha near the peak does not cancel catastrophically. Zero for m.z <= 0.
GONIO_INLINE float ggx_D(vec3 m, float alpha) {
    if (m.z <= 0.0f) return 0.0f;
    float a2 = alpha * alpha;
    float s = (m.x * m.x + m.y * m.y) / a2 + m.z * m.z;
    return 1.0f / (PI * a2 * s * s);
}

// Smith Lambda for GGX (Heitz 2014, "Understanding the masking-shadowing function", eq. 72), using |w.z|,
// so it serves directions on either side. Infinite at w.z == 0 (G then goes to 0, never NaN).
GONIO_INLINE float ggx_lambda(vec3 w, float alpha) {
    float z2 = w.z * w.z;
    float t2 = (w.x * w.x + w.y * w.y) / z2;        // tan^2 theta (inf at the horizon)
    return 0.5f * (sqrt(1.0f + alpha * alpha * t2) - 1.0f);
}

GONIO_INLINE float ggx_G1(vec3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }

// Height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wi) + Lambda(wo)) (Heitz 2014, eq. 99),
// used for reflection and for transmission alike (as pbrt-v4 does).
GONIO_INLINE float ggx_G2(vec3 wi, vec3 wo, float alpha) {
    return 1.0f / (1.0f + ggx_lambda(wi, alpha) + ggx_lambda(wo, alpha));
}

// The weight of visible-normal sampling, G2(wi, wo) / G1(wi) = (1 + Lambda(wi)) / (1 + Lambda(wi) + Lambda(wo)).
GONIO_INLINE float ggx_G2_over_G1(vec3 wi, vec3 wo, float alpha) {
    float li = ggx_lambda(wi, alpha);
    return (1.0f + li) / (1.0f + li + ggx_lambda(wo, alpha));
}

// Distribution of visible normals D_wi(m) = G1(wi) max(0, wi.m) D(m) / wi.z (Heitz 2014, eq. 38).
GONIO_INLINE float ggx_visible_normal_pdf(vec3 wi, vec3 m, float alpha) {
    float wm = dot(wi, m);
    if (wm <= 0.0f) return 0.0f;
    return ggx_G1(wi, alpha) * wm * ggx_D(m, alpha) / wi.z;
}

// Sample m from D_wi (wi.z > 0). Dupuy & Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps",
// Listing 3: stretch to alpha = 1, sample the spherical cap z in [-wi.z, 1], add wi, unstretch.
GONIO_INLINE vec3 sample_ggx_visible_normal(vec3 wi, float alpha, float u1, float u2) {
    vec3 wi_std = normalize(vec3(wi.x * alpha, wi.y * alpha, wi.z));
    float phi = 2.0f * PI * u1;
    float z = (1.0f - u2) * (1.0f + wi_std.z) - wi_std.z;
    float r = sqrt(clamp(1.0f - z * z, 0.0f, 1.0f));
    vec3 h = vec3(r * cos(phi), r * sin(phi), z) + wi_std;
    return normalize(vec3(h.x * alpha, h.y * alpha, max(h.z, 1e-9f)));
}

// Cosine-weighted hemisphere (Malley's method): pdf = w.z / pi.
GONIO_INLINE vec3 sample_cosine_hemisphere(float u1, float u2) {
    float r = sqrt(u1);
    float phi = 2.0f * PI * u2;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u1)));
}
#endif
