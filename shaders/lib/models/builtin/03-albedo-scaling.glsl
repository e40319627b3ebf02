// gonio-model: albedo-scaling
// citation: OpenPBR Surface v1.1 layering (Andersson et al. 2024), as used by Autodesk Standard Surface (Georgiev
//   et al. 2019)
// family: production
// summary: f_coat + T_coat (1 - E_coat(v)) f_base(l, v): albedo scaling with view-dependent coat absorption
// stacks: one dielectric coat over a Lambertian or conductor base
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - E_coat(v), the coat's albedo seen from v, not from l)
// plan: coat
// tables: coat-albedo
// refuses: scattering-medium = {id} has no scattering medium ({layer}: its single-scattering albedo is above 0); it
//   would take the optical depth as absorption alone
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian or conductor base (models/common.glsl
//   base_brdf), not a {base}
// refuses: not-two-layers = {id} is implemented for one dielectric coat over an opaque base; this stack has {layers}
//   layers
//
// models/builtin/03-albedo-scaling.glsl: `albedo-scaling`, the layering of production shading models: OpenPBR Surface
// v1.1 (Andersson et al. 2024, section "Layering", the non-reciprocal albedo-scaling form with coat
// absorption) and Autodesk Standard Surface (Georgiev et al. 2019), which the OpenPBR text says uses it:
//   f = f_coat(l, v) + T_coat(l, v) (1 - E_coat(v)) f_base(l, v)
// f_coat is the top interface's reflection, E_coat(v) its directional albedo (computed by gonio for this
// stack, host/models/stack_tables.cpp), T_coat = exp(-tau (1/mu_l + 1/mu_v)) with the Snell-refracted cosines, and the
// base is evaluated at the unrefracted directions with its own roughness. The coat's darkening and roughening
// extensions of OpenPBR are not included. Not reciprocal (E_coat of v only).
// The includer provides float model_coat_albedo(float mu): E_coat at cos theta = mu.
#ifndef GONIO_MODEL_ALBEDO_SCALING_GLSL
#define GONIO_MODEL_ALBEDO_SCALING_GLSL
#include "models/common.glsl"

GONIO_INLINE vec3 model_albedo_scaling(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += vec3(top_reflection(l, v, p.alpha0, p.eta));
    if ((terms & TERM_BASE) != 0u) {
        vec3 l1 = refract_into_coat(l, p.eta), v1 = refract_into_coat(v, p.eta);
        f += (1.0f - model_coat_albedo(v.z)) * coat_attenuation(p.tau, l1, v1) * base_brdf(p, l, v, p.alpha1);
    }
    return f;
}
#endif
