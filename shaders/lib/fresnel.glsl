// fresnel.glsl: exact unpolarised Fresnel reflectance.
#ifndef GONIO_FRESNEL_GLSL
#define GONIO_FRESNEL_GLSL
#include "compat.glsl"

// Dielectric interface. cos_i = cosine between the incident direction and the normal on the incident side
// (>= 0); eta = n_transmitted / n_incident. Returns 1 under total internal reflection.
// Born & Wolf, Principles of Optics, 1.5.2 (r_s, r_p amplitudes), averaged over the two polarisations.
GONIO_INLINE float fresnel_dielectric(float cos_i, float eta) {
    float c = clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = (1.0f - c * c) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;
    float cos_t = sqrt(1.0f - sin2_t);
    float rs = (c - eta * cos_t) / (c + eta * cos_t);
    float rp = (eta * c - cos_t) / (eta * c + cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

// The same reflectance with few divisions (sampling path): inv_eta2 = 1 / eta^2; also returns the cosine of the
// refracted direction (0 under total internal reflection, where F = 1). rs^2 + rp^2 over one common denominator.
GONIO_INLINE float fresnel_dielectric_cos_t(float cos_i, float eta, float inv_eta2, OUT(float) cos_t) {
    float c = clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = (1.0f - c * c) * inv_eta2;
    cos_t = sqrt(max(1.0f - sin2_t, 0.0f));
    float a = c - eta * cos_t, b = c + eta * cos_t;      // rs = a / b
    float e = eta * c - cos_t, f = eta * c + cos_t;      // rp = e / f
    float bf = b * f;
    float F = 0.5f * ((a * f) * (a * f) + (e * b) * (e * b)) / (bf * bf);
    return sin2_t >= 1.0f ? 1.0f : F;
}

// Cosine of the refracted direction for a dielectric interface, or -1 under total internal reflection.
GONIO_INLINE float refracted_cos(float cos_i, float eta) {
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    return sin2_t >= 1.0f ? -1.0f : sqrt(1.0f - sin2_t);
}

// Conductor with complex relative IOR eta + i k (relative to the medium above), per channel.
// Real-arithmetic form of the exact unpolarised reflectance (as in Mitsuba's fresnelConductorExact;
// Born & Wolf 14.2). cos_i in [0, 1].
GONIO_INLINE vec3 fresnel_conductor(float cos_i, vec3 eta, vec3 k) {
    float c = clamp(cos_i, 0.0f, 1.0f);
    float c2 = c * c;
    float s2 = 1.0f - c2;
    vec3 t1 = eta * eta - k * k - vec3(s2);
    vec3 a2b2 = sqrt(t1 * t1 + 4.0f * eta * eta * k * k);
    vec3 a = sqrt(max(0.5f * (a2b2 + t1), vec3(0.0f)));
    // rs = n1 / d1, rp = rs n2 / d2, so (rs + rp) / 2 = n1 (d2 + n2) / (2 d1 d2): one division per channel
    vec3 n1 = a2b2 + vec3(c2) - 2.0f * c * a, d1 = a2b2 + vec3(c2) + 2.0f * c * a;
    vec3 n2 = a2b2 * c2 + vec3(s2 * s2) - 2.0f * c * s2 * a, d2 = a2b2 * c2 + vec3(s2 * s2) + 2.0f * c * s2 * a;
    return 0.5f * n1 * (d2 + n2) / (d1 * d2);
}
#endif
