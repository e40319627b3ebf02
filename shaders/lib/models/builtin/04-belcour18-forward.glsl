// gonio-model: belcour18-forward
// citation: Belcour 2018, ACM TOG 37(4) 73, sections 4-6 (atomic operators, adding)
// family: Belcour 2018
// summary: sum of GGX lobes (separable Smith G, as the official code) from energy/variance statistics of the
//   incident direction, FGD and TIR tables (separable G); no TIR term below an absorbing medium (as the official
//   code)
// stacks: any number of dielectric interfaces over a conductor base, or a slab (dielectric stack in one medium);
//   not a Lambertian base
// represents: dielectric-stack-over-conductor, slab
// reciprocal: no
// energy-conserving: yes
// variant: +g2 = convention g2: with height-correlated Smith G2 in its GGX lobes and FGD/TIR tables (gonio's
//   alternative to the separable G of the official code)
// variant: +tir = convention tir-below-media: with the TIR term kept for an interface over an absorbing medium (the
//   official code loses it there)
// variant: +g2+tir = convention g2, tir-below-media: with both: height-correlated G2 and the TIR term kept below
//   absorbing media
// plan: lobes
// refuses: backward-scattering-medium = {id} takes forward-scattering media only ({layer} with phase_g {phase_g}): its
//   Henyey-Greenstein variance ((1 - g) / g)^0.8 / (1 + g) is defined for g in (0, 1] (Belcour 2018 section 5)
// refuses: lambertian-base = {id} is limited to forward propagation: light entering a Lambertian base never leaves it
//   on reflection (Bati et al. 2019 section 2.2)
// refuses: substrate-not-exterior = {id}: a transmitted lobe into a substrate of another IOR than the exterior's is
//   not implemented (only slabs: substrate IOR {substrate_ior} differs from the exterior's {exterior_ior})
//
// models/builtin/04-belcour18-forward.glsl: `belcour18-forward`, Belcour 2018's adding of atomic operators with the
// statistics of the incident direction (models/belcour18.glsl, BELCOUR_FORWARD). Energy-conserving: the lobe
// energies sum to at most 1 (the adding equations) and each GGX lobe (F = 1) reflects at most its energy.
// The variants are the same code with other conventions (docs/MODELS.md "Conventions").
#ifndef GONIO_MODEL_BELCOUR18_FORWARD_GLSL
#define GONIO_MODEL_BELCOUR18_FORWARD_GLSL
#include "models/belcour18.glsl"

// models.comp's pre-pass (KERNEL 2): the lobes at mu = cos theta_i, once per dispatch
#define GONIO_MODEL_LOBES(mu, tables) belcour_lobes(mu, tables)
GONIO_INLINE vec3 model_belcour18_forward(CoatParams p, uint terms, vec3 l, vec3 v) {
    return model_belcour18_entry(BELCOUR_FORWARD, terms, l, v);
}
#endif
