// gonio-model: belcour18-toplobe
// citation: Bati, Pacanowski & Barla 2019 section 4.2, on Belcour 2018
// family: Belcour 2018
// summary: exact top-interface BRDF f_r0 for lobe 0, belcour18-forward for the lobes below
// stacks: as belcour18-forward
// represents: dielectric-stack-over-conductor, slab
// reciprocal: no
// energy-conserving: no (the exact lobe 0 reflects the exact top albedo while the lobes below get 1 - FGD from the
//   table; near grazing the two differ (not bounded by construction; no excess found on the hard cases with the
//   separable tables: largest 1.000))
// variant: +g2 = convention g2: with height-correlated Smith G2 in its GGX lobes and FGD/TIR tables (gonio's
//   alternative to the separable G of the official code)
// variant: +tir = convention tir-below-media: with the TIR term kept for an interface over an absorbing medium (the
//   official code loses it there)
// variant: +g2+tir = convention g2, tir-below-media: with both: height-correlated G2 and the TIR term kept below
//   absorbing media
// variant-energy-note: +g2 = as belcour18-toplobe (1.003 measured at 89.9 degrees on stacks/hard/tir-trap-slab)
// variant-energy-note: +tir = as belcour18-toplobe (not bounded by construction; no excess found on the hard cases:
//   largest 1.000)
// variant-energy-note: +g2+tir = as belcour18-toplobe (1.003 measured at 89.9 degrees on
//   stacks/hard/tir-trap-slab)
// plan: lobes
// refuses: backward-scattering-medium = {id} takes forward-scattering media only ({layer} with phase_g {phase_g}): its
//   Henyey-Greenstein variance ((1 - g) / g)^0.8 / (1 + g) is defined for g in (0, 1] (Belcour 2018 section 5)
// refuses: lambertian-base = {id} is limited to forward propagation: light entering a Lambertian base never leaves it
//   on reflection (Bati et al. 2019 section 2.2)
// refuses: substrate-not-exterior = {id}: a transmitted lobe into a substrate of another IOR than the exterior's is
//   not implemented (only slabs: substrate IOR {substrate_ior} differs from the exterior's {exterior_ior})
//
// models/builtin/06-belcour18-toplobe.glsl: `belcour18-toplobe`, Bati et al. 2019's fix of Belcour 2018 (section
// 4.2): the exact top-interface BRDF for lobe 0, the forward model's lobes below (models/belcour18.glsl,
// BELCOUR_TOPLOBE).
#ifndef GONIO_MODEL_BELCOUR18_TOPLOBE_GLSL
#define GONIO_MODEL_BELCOUR18_TOPLOBE_GLSL
#include "models/belcour18.glsl"

// models.comp's pre-pass (KERNEL 2): the lobes at mu = cos theta_i, once per dispatch
#define GONIO_MODEL_LOBES(mu, tables) belcour_lobes(mu, tables)
GONIO_INLINE vec3 model_belcour18_toplobe(CoatParams p, uint terms, vec3 l, vec3 v) {
    return model_belcour18_entry(BELCOUR_TOPLOBE, terms, l, v);
}
#endif
