// beckmann.glsl: the isotropic Beckmann microfacet distribution (Beckmann & Spizzichino 1963; Walter et al. 2007,
// eqs. 25-27), its exact Smith Lambda (Heitz 2014, "Understanding the masking-shadowing function", eq. 80; no rational
// approximation), and visible-normal sampling (Heitz & d'Eon 2014, "Importance sampling microfacet-based BSDFs using
// the distribution of visible normals": stretch to alpha = 1, sample the slopes of the visible normals, unstretch;
// the slope along the incident plane by a safeguarded Newton inversion of its CDF in erf's domain, as Jakob 2014 did
// for Mitsuba, since the paper's closed-form fit is discontinuous). Directions in the interface's local frame, z the
// macro-normal, as in ggx.glsl.
#ifndef GONIO_BECKMANN_GLSL
#define GONIO_BECKMANN_GLSL
#include "compat.glsl"
#include "erf.glsl"

// D(m) = exp(-tan^2 theta_m / alpha^2) / (pi alpha^2 cos^4 theta_m); zero for m.z <= 0.
GONIO_INLINE float beckmann_D(vec3 m, float alpha) {
    if (m.z <= 0.0f) return 0.0f;
    float a2 = alpha * alpha;
    float c2 = m.z * m.z;
    float t2 = (m.x * m.x + m.y * m.y) / c2;
    return exp(-t2 / a2) / (PI * a2 * c2 * c2);
}

// Lambda(w) = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2, a = 1 / (alpha tan theta) = |w.z| / (alpha sin theta), using
// |w.z| so that it serves either side. 0 at normal incidence (a infinite), infinite at the horizon (a = 0).
GONIO_INLINE float beckmann_lambda(vec3 w, float alpha) {
    float a = abs(w.z) / (alpha * sqrt(w.x * w.x + w.y * w.y));
    return 0.5f * (exp(-a * a) * INV_SQRT_PI / a - erfc_nonnegative(a));
}

GONIO_INLINE float beckmann_G1(vec3 w, float alpha) { return 1.0f / (1.0f + beckmann_lambda(w, alpha)); }

// Distribution of visible normals D_wi(m) = G1(wi) max(0, wi.m) D(m) / wi.z (Heitz 2014, eq. 38).
GONIO_INLINE float beckmann_visible_normal_pdf(vec3 wi, vec3 m, float alpha) {
    float wm = dot(wi, m);
    if (wm <= 0.0f) return 0.0f;
    return beckmann_G1(wi, alpha) * wm * beckmann_D(m, alpha) / wi.z;
}

// The slopes (x along the incident plane, y across it) of a visible normal of the unit Beckmann surface seen from
// theta (cos_t, sin_t; theta beyond 90 degrees too: a direction below the horizon, microsurface_walk.glsl). x has the
// density proportional to (cos_t - x sin_t) exp(-x^2) on x < cot theta, whose CDF, written in q = 1 + erf(x) =
// erfc(-x), is C(q) = (q + tan theta exp(-x^2) / sqrt(pi)) / (q_max + tan theta exp(-cot^2 theta) / sqrt(pi)),
// q_max = erfc(-cot theta). q, not erf(x), keeps its digits where x is far in the lower tail (below the horizon, where
// 1 + erf(cot theta) is small): erfc and erfc^-1 in their tails. C(q) = u1 is solved by Newton's method
// (dC/dq = (1 - x tan theta) / norm), each step kept inside the bracket [lo, hi] that C's sign keeps (bisection where
// it would leave it), and the result too. y is a unit Gaussian independent of x: erfinv(2 u2 - 1). At normal
// incidence (tan theta = 0) C(q) = q / 2 exactly.
GONIO_INLINE vec2 beckmann_visible_slopes_unit(float cos_t, float sin_t, float u1, float u2) {
    float tan_t = sin_t / cos_t;
    float cot_t = cos_t / sin_t;   // infinite at normal incidence: erfc(-inf) = 2, exp 0
    float q_max = cot_t >= 0.0f ? 2.0f - erfc_nonnegative(cot_t) : erfc_nonnegative(-cot_t);
    float lo = 0.0f, hi = q_max;
    float u = max(u1, 1e-7f);
    float norm = 1.0f / (q_max + INV_SQRT_PI * tan_t * exp(-cot_t * cot_t));
    float q = mix(lo, hi, u);   // the CDF's value on a straight line: a start inside the bracket
    for (int it = 0; it < 24; ++it) {
        if (!(q > lo && q <= hi)) q = 0.5f * (lo + hi);   // also catches a NaN step
        float x = -erfcinv_any(q);
        float value = norm * (q + INV_SQRT_PI * tan_t * exp(-x * x)) - u;
        if (abs(value) < 2e-7f) break;
        if (value > 0.0f) hi = q;
        else lo = q;
        q -= value / (norm * (1.0f - x * tan_t));
    }
    q = q > lo && q <= hi ? q : 0.5f * (lo + hi);   // the last step may have left the bracket
    return vec2(-erfcinv_any(q), erfinv_any(2.0f * max(u2, 1e-7f) - 1.0f));
}

// Sample m from D_wi (wi on either side of the horizon), alpha > 0.
GONIO_INLINE vec3 sample_beckmann_visible_normal(vec3 wi, float alpha, float u1, float u2) {
    vec3 ws = normalize(vec3(wi.x * alpha, wi.y * alpha, wi.z));   // stretched to alpha = 1
    float r = sqrt(ws.x * ws.x + ws.y * ws.y);
    vec2 s = beckmann_visible_slopes_unit(ws.z, r, u1, u2);
    float c = r > 0.0f ? ws.x / r : 1.0f, sn = r > 0.0f ? ws.y / r : 0.0f;   // wi's azimuth
    float sx = (c * s.x - sn * s.y) * alpha, sy = (sn * s.x + c * s.y) * alpha;   // turned, unstretched
    return normalize(vec3(-sx, -sy, 1.0f));
}
#endif
