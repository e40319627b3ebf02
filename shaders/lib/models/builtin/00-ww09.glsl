// gonio-model: ww09
// citation: Weidlich & Wilkie 2009 (SIGGRAPH Asia course), variant of Weidlich & Wilkie 2007; Bati et al. 2019
//   eq. 2
// family: Weidlich-Wilkie
// summary: T01/T10 from the top microfacet normal, base at unrefracted directions, TIR term t = (1 - G) + T10 G
// stacks: one dielectric coat over a Lambertian or conductor base
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: yes
// energy-conserving: no (the base is added to the full top reflection without the energy the top reflects;
//   t = (1 - G) + T10 G can exceed T10)
// plan: coat
// refuses: scattering-medium = {id} has no scattering medium ({layer}: its single-scattering albedo is above 0); it
//   would take the optical depth as absorption alone
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian or conductor base (models/common.glsl
//   base_brdf), not a {base}
// refuses: not-two-layers = {id} is implemented for one dielectric coat over an opaque base; this stack has {layers}
//   layers
//
// models/builtin/00-ww09.glsl: `ww09`, Weidlich & Wilkie's own course variant (SIGGRAPH Asia 2009 course, as read by
// Bati et al. 2019, section 2.1 and 4.1) of Weidlich & Wilkie 2007, Equation 2 of Bati et al.:
//   f = f_r0(l, v) + T01 f_r1(l, v) a t,   t = (1 - G) + T10 G
// T01 and T10 with the top microfacet normal h0; the refracted directions (l1, v1), refracted about h0,
// enter only the absorption a; the base BRDF is evaluated at the unrefracted (l, v) with its own roughness;
// G is the top interface's masking-shadowing; no solid-angle factor.
#ifndef GONIO_MODEL_WW09_GLSL
#define GONIO_MODEL_WW09_GLSL
#include "models/common.glsl"

GONIO_INLINE vec3 model_ww09(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += vec3(top_reflection(l, v, p.alpha0, p.eta));
    if ((terms & TERM_BASE) != 0u) {
        vec3 h = normalize(l + v);
        float cl = dot(l, h), cv = dot(v, h);
        float t01 = 1.0f - fresnel_dielectric(cl, p.eta);
        float t10 = 1.0f - fresnel_dielectric(cv, p.eta);
        // refraction about h0 (entering the denser coat: no total internal reflection)
        vec3 l1 = refract_through(l, h, cl, refracted_cos(cl, p.eta), p.eta);
        vec3 v1 = refract_through(v, h, cv, refracted_cos(cv, p.eta), p.eta);
        vec3 a = exp(-p.tau * (1.0f / max(abs(l1.z), 1e-6f) + 1.0f / max(abs(v1.z), 1e-6f)));
        float G = ggx_G2(l, v, p.alpha0);
        float t = (1.0f - G) + t10 * G;
        f += t01 * t * base_brdf(p, l, v, p.alpha1) * a;
    }
    return f;
}
#endif
