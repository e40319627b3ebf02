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
// table: coat-albedo 65
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
// f_coat is the top interface's reflection, E_coat(v) its directional albedo (the coat-albedo set this file
// declares, which openpbr and standard-surface also read; computed on the host for the stack), T_coat =
// exp(-tau (1/mu_l + 1/mu_v)) with the Snell-refracted cosines, and the base is evaluated at the unrefracted
// directions with its own roughness. The coat's darkening and roughening extensions of OpenPBR are not included. Not
// reciprocal (E_coat of v only).
#ifndef GONIO_MODEL_ALBEDO_SCALING_GLSL
#define GONIO_MODEL_ALBEDO_SCALING_GLSL
#include "models/common.glsl"

GONIO_INLINE vec3 model_albedo_scaling(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += vec3(top_reflection(l, v, p.alpha0, p.eta));
    if ((terms & TERM_BASE) != 0u) {
        vec3 l1 = refract_into_coat(l, p.eta), v1 = refract_into_coat(v, p.eta);
        const float e_coat = model_stack_table_at(STACK_TABLE_COAT_ALBEDO, COAT_ALBEDO_NODES, v.z);
        f += (1.0f - e_coat) * coat_attenuation(p.tau, l1, v1) * base_brdf(p, l, v, p.alpha1);
    }
    return f;
}

#ifdef __cplusplus
// coat-albedo (the host, model_twin.h): E_coat(mu) = the integral of f_r0(l, v) cos(theta_v) dv over the hemisphere
// (common.glsl's top_reflection: dielectric Fresnel, GGX D, height-correlated G2) at the set's nodes of mu, for a
// coat over an opaque base and over a dielectric base: the FGD of the coat's interface with G2 by gonio's one
// quadrature of an interface's albedo (models/fgd_quadrature.glsl, which Belcour's tables also call); mu = 0 is its
// limit mu -> 0+. Clamped to 1, so that 1 - E_coat, the base's weight, is never negative.
GONIO_INLINE void albedo_scaling_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_COAT_ALBEDO) == 0u || table_stack_shape(s) == TABLE_SHAPE_OTHER) return;
    const CoatParams p = coat_params(s.layers[0], s.layers[1]);
    for (uint i = 0u; i < COAT_ALBEDO_NODES; ++i)
        model_stack_table_store(
            STACK_TABLE_COAT_ALBEDO + i,
            min(1.0f,
                fgd_quadrature(s.layers[0], coat_albedo_node_mu(i), p.alpha0, true, FGD_NODES_THETA, FGD_NODES_PHI).x));
}
#define GONIO_MODEL_TABLES(s, sets) albedo_scaling_tables(s, sets)
#endif
#endif
