// ggx.glsl: the isotropic GGX (Trowbridge-Reitz) microfacet distribution, height-correlated Smith
// masking-shadowing (and the separable form that the analytic models' official codes use), and visible-normal
// sampling. All directions in the local frame of the interface: z is the macro-normal, pointing to the side the
// light arrives from.
#ifndef GONIO_GGX_GLSL
#define GONIO_GGX_GLSL
#include "compat.glsl"

// normalize(v) for vectors whose length is within a few orders of magnitude of 1 (no underflow or overflow of
// dot(v, v)): one square root and one division. The GLSL normalize() guards against both by first dividing v by
// its largest component (Mesa's NIR lowering): four divisions, and divisions are the scarce resource of a CPU
// vector unit (lavapipe: each 8-wide vdivps occupies the divider about 5 cycles).
GONIO_INLINE vec3 normalize_unit_scale(vec3 v) { return v * (1.0f / sqrt(dot(v, v))); }

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

// Separable masking-shadowing G1(wi) G1(wo) (Smith 1967; Walter et al. 2007, eq. 23): what Mitsuba 0.6's
// MicrofacetDistribution::G computes, and with it the official codes of the layered models (Belcour 2018 through
// its ports, Randrianandrasana et al. 2021; docs/MODELS.md). The reference walk does not use it.
GONIO_INLINE float ggx_G2_separable(vec3 wi, vec3 wo, float alpha) {
    return ggx_G1(wi, alpha) * ggx_G1(wo, alpha);
}

// The weight of visible-normal sampling, G2(wi, wo) / G1(wi) = (1 + Lambda(wi)) / (1 + Lambda(wi) + Lambda(wo)).
// With S = sqrt(1 + alpha^2 tan^2) = A / |z|, A = sqrt(z^2 + alpha^2 (x^2 + y^2)), 1 + Lambda = (1 + S) / 2, so
// the ratio is (1 + S_i) / (S_i + S_o) = (|z_i| + A_i) |z_o| / (A_i |z_o| + A_o |z_i|): one division, not three
// (and 0, not NaN, for wo at the horizon).
GONIO_INLINE float ggx_G2_over_G1(vec3 wi, vec3 wo, float alpha) {
    float a2 = alpha * alpha;
    float zi = abs(wi.z), zo = abs(wo.z);
    float ai = sqrt(wi.z * wi.z + a2 * (wi.x * wi.x + wi.y * wi.y));
    float ao = sqrt(wo.z * wo.z + a2 * (wo.x * wo.x + wo.y * wo.y));
    return (zi + ai) * zo / (ai * zo + ao * zi);
}

// Distribution of visible normals D_wi(m) = G1(wi) max(0, wi.m) D(m) / wi.z (Heitz 2014, eq. 38).
GONIO_INLINE float ggx_visible_normal_pdf(vec3 wi, vec3 m, float alpha) {
    float wm = dot(wi, m);
    if (wm <= 0.0f) return 0.0f;
    return ggx_G1(wi, alpha) * wm * ggx_D(m, alpha) / wi.z;
}

// Sample m from D_wi (wi on either side of the horizon: the cap below then shrinks to z in [-wi.z, 1], and h = the
// cap's point + wi still has the density <wi.h> D(h) on the upper hemisphere; microsurface_walk.glsl). Dupuy &
// Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps",
// Listing 3: stretch to alpha = 1, sample the spherical cap z in [-wi.z, 1], add wi, unstretch.
GONIO_INLINE vec3 sample_ggx_visible_normal(vec3 wi, float alpha, float u1, float u2) {
    vec3 wi_std = normalize_unit_scale(vec3(wi.x * alpha, wi.y * alpha, wi.z));
    float phi = 2.0f * PI * u1;
    float z = (1.0f - u2) * (1.0f + wi_std.z) - wi_std.z;
    float r = sqrt(clamp(1.0f - z * z, 0.0f, 1.0f));
    vec3 h = vec3(r * cos(phi), r * sin(phi), z) + wi_std;
    return normalize_unit_scale(vec3(h.x * alpha, h.y * alpha, max(h.z, 1e-9f)));
}

// Cosine-weighted hemisphere (Malley's method): pdf = w.z / pi.
GONIO_INLINE vec3 sample_cosine_hemisphere(float u1, float u2) {
    float r = sqrt(u1);
    float phi = 2.0f * PI * u2;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - u1)));
}
#endif
