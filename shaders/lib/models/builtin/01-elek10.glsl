// gonio-model: elek10
// citation: Elek 2010 (CESCG), as described by Bati et al. 2019 section 2.1
// family: Weidlich-Wilkie
// summary: as ww09 but the base at Snell-refracted directions, alpha1 <- max(alpha0, alpha1)
// stacks: one dielectric coat over a Lambertian or conductor base
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: yes
// energy-conserving: no (as ww09)
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
// models/builtin/01-elek10.glsl: `elek10`, Elek 2010 (CESCG, "Layered materials in real-time rendering"), as described
// by Bati et al. 2019, section 2.1: Equation 2 with T01 and T10 from the top microfacet normal h0, the base
// evaluated at the refracted directions (l1, v1) (Snell about n), and the roughness rule
// alpha1 <- max(alpha0, alpha1); t = (1 - G) + T10 G; no solid-angle factor.
#ifndef GONIO_MODEL_ELEK10_GLSL
#define GONIO_MODEL_ELEK10_GLSL
#include "models/common.glsl"

GONIO_INLINE vec3 model_elek10(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += vec3(top_reflection(l, v, p.alpha0, p.eta));
    if ((terms & TERM_BASE) != 0u) {
        vec3 h = normalize(l + v);
        float t01 = 1.0f - fresnel_dielectric(dot(l, h), p.eta);
        float t10 = 1.0f - fresnel_dielectric(dot(v, h), p.eta);
        vec3 l1 = refract_into_coat(l, p.eta), v1 = refract_into_coat(v, p.eta);
        float G = ggx_G2(l, v, p.alpha0);
        float t = (1.0f - G) + t10 * G;
        f += t01 * t * base_brdf(p, l1, v1, max(p.alpha0, p.alpha1)) * coat_attenuation(p.tau, l1, v1);
    }
    return f;
}
#endif
