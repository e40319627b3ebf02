// gonio-model: ww-corrected
// citation: Bati, Pacanowski & Barla 2019, eq. 4
// family: Weidlich-Wilkie
// summary: geometric normal for T01, T10 and refraction, 1/eta^2 solid-angle factor, Elek's roughness rule
// stacks: one dielectric coat over a Lambertian or conductor base
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: yes
// energy-conserving: yes
// plan: coat-refracted
// refuses: scattering-medium = {id} has no scattering medium ({layer}: its single-scattering albedo is above 0); it
//   would take the optical depth as absorption alone
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian or conductor base (models/common.glsl
//   base_brdf), not a {base}
// refuses: not-two-layers = {id} is implemented for one dielectric coat over an opaque base; this stack has {layers}
//   layers
//
// models/builtin/02-ww-corrected.glsl: `ww-corrected`, Bati, Pacanowski & Barla 2019, Equation 4:
//   f = f_r0(l, v) + T01 f_r1(l1, v1) a T10 / eta^2
// with the geometric normal n for T01, T10 and for refracting l, v into (l1, v1) (Snell), the solid-angle
// factor 1/eta^2 (Ishimaru 1978, p. 154), T10 in place of the TIR term t, and Elek's roughness rule
// alpha1 <- max(alpha0, alpha1). a = exp(-tau (1/cos l1 + 1/cos v1)).
#ifndef GONIO_MODEL_WW_CORRECTED_GLSL
#define GONIO_MODEL_WW_CORRECTED_GLSL
#include "models/common.glsl"

GONIO_INLINE vec3 model_ww_corrected(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += vec3(top_reflection(l, v, p.alpha0, p.eta));
    if ((terms & TERM_BASE) != 0u) {
        vec3 l1 = refract_into_coat(l, p.eta), v1 = refract_into_coat(v, p.eta);
        float t01 = 1.0f - fresnel_dielectric(l.z, p.eta);
        float t10 = 1.0f - fresnel_dielectric(v.z, p.eta);
        f += t01 * t10 / (p.eta * p.eta) * base_brdf(p, l1, v1, max(p.alpha0, p.alpha1)) *
             coat_attenuation(p.tau, l1, v1);
    }
    return f;
}
#endif
