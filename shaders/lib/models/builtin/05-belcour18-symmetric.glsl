// gonio-model: belcour18-symmetric
// citation: Belcour 2018, section 7.2 (symmetric model)
// family: Belcour 2018
// summary: as belcour18-forward with statistics from |h.l|, h = normalize(l + v): reciprocal
// stacks: dielectric interfaces over a conductor base (reflection only)
// represents: dielectric-stack-over-conductor
// reciprocal: yes
// energy-conserving: no (each direction v has its own lobe energies (from |h.l|): their sum over v is not bounded
//   by 1 (1.215 measured at 89.9 degrees on stacks/hard/ior-3-metal))
// variant: +g2 = convention g2: with height-correlated Smith G2 in its GGX lobes and FGD/TIR tables (gonio's
//   alternative to the separable G of the official code)
// variant: +tir = convention tir-below-media: with the TIR term kept for an interface over an absorbing medium (the
//   official code loses it there)
// variant: +g2+tir = convention g2, tir-below-media: with both: height-correlated G2 and the TIR term kept below
//   absorbing media
// variant-energy-note: +g2 = as belcour18-symmetric (1.318 measured at 89.9 degrees on stacks/hard/ior-3-metal)
// variant-energy-note: +tir = as belcour18-symmetric (1.040 measured at 89.9 degrees on stacks/hard/ior-3-metal)
// variant-energy-note: +g2+tir = as belcour18-symmetric (1.069 measured at 89.9 degrees on
//   stacks/hard/ior-3-metal)
// plan: lobes-symmetric
// refuses: backward-scattering-medium = {id} takes forward-scattering media only ({layer} with phase_g {phase_g}): its
//   Henyey-Greenstein variance ((1 - g) / g)^0.8 / (1 + g) is defined for g in (0, 1] (Belcour 2018 section 5)
// refuses: lambertian-base = {id} is limited to forward propagation: light entering a Lambertian base never leaves it
//   on reflection (Bati et al. 2019 section 2.2)
// refuses: transmissive = {id} is defined for reflection (its statistics use the reflection half-vector); this stack
//   is transmissive
//
// models/builtin/05-belcour18-symmetric.glsl: `belcour18-symmetric`, Belcour 2018 section 7.2: the adding loop of
// models/belcour18.glsl with the statistics of mu = |h.l|, h = normalize(l + v) (BELCOUR_SYMMETRIC). The energy
// excesses are measured on the hard cases (tests/test_hard_cases.cpp).
#ifndef GONIO_MODEL_BELCOUR18_SYMMETRIC_GLSL
#define GONIO_MODEL_BELCOUR18_SYMMETRIC_GLSL
#include "models/belcour18.glsl"

// models.comp's pre-pass (KERNEL 2): the lobes at BELCOUR_MU_NODES nodes of mu = |h.l| (GONIO_MODEL_LOBE_TABLE),
// read by model_belcour18_symmetric_table; bins next to the lobes' jump at mu_jump evaluate the adding loop itself
// (GONIO_MODEL_EXACT)
#define GONIO_MODEL_LOBES(mu, tables) belcour_lobes(mu, tables)
#define GONIO_MODEL_LOBE_TABLE 1
#define GONIO_MODEL_EXACT(terms, l, v) model_belcour18(BELCOUR_SYMMETRIC, terms, l, v)
GONIO_INLINE vec3 model_belcour18_symmetric(CoatParams p, uint terms, vec3 l, vec3 v) {
#ifdef BELCOUR_PRECOMPUTED_LOBES
    return model_belcour18_symmetric_table(terms, l, v);
#else
    return model_belcour18(BELCOUR_SYMMETRIC, terms, l, v);
#endif
}
#endif
