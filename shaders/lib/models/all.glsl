// models/all.glsl: every analytic model, by index (the order of host/models/model_registry.cpp's registry).
// Models 0-3 take the two-layer CoatParams; Belcour's (4-6) and tm21 (7) read the whole stack through model_layer().
#ifndef GONIO_MODELS_ALL_GLSL
#define GONIO_MODELS_ALL_GLSL
#include "ww09.glsl"
#include "elek10.glsl"
#include "ww_corrected.glsl"
#include "albedo_scaling.glsl"
#include "belcour18.glsl"
#include "tm21.glsl"
#include "model_ids.glsl"


GONIO_INLINE vec3 eval_model(uint model, CoatParams p, uint terms, vec3 l, vec3 v) {
#if GONIO_HAS_MODEL(0)
    if (model == MODEL_WW09) return model_ww09(p, terms, l, v);
#endif
#if GONIO_HAS_MODEL(1)
    if (model == MODEL_ELEK10) return model_elek10(p, terms, l, v);
#endif
#if GONIO_HAS_MODEL(2)
    if (model == MODEL_WW_CORRECTED) return model_ww_corrected(p, terms, l, v);
#endif
#if GONIO_HAS_MODEL(3)
    if (model == MODEL_ALBEDO_SCALING) return model_albedo_scaling(p, terms, l, v);
#endif
#ifdef BELCOUR_LOBES_OF_MU
    // render.comp: every variant's lobes from the table over mu (l changes from one evaluation to the next)
#if GONIO_HAS_MODEL(5)
    if (model == MODEL_BELCOUR18_SYMMETRIC) return model_belcour18_symmetric_table(terms, l, v);
#endif
#if GONIO_HAS_MODEL(7)
    if (model == MODEL_TM21) return model_belcour18_lobes_of_mu(BELCOUR_TOPLOBE, terms, l, v);   // exact lobe 0
#endif
#if GONIO_HAS_MODEL(4) || GONIO_HAS_MODEL(6)
    return model_belcour18_lobes_of_mu(model - MODEL_BELCOUR18_FORWARD, terms, l, v);
#else
    return vec3(0.0f);
#endif
#elif defined(BELCOUR_PRECOMPUTED_LOBES)
#if GONIO_HAS_MODEL(5)
    if (model == MODEL_BELCOUR18_SYMMETRIC) return model_belcour18_symmetric_table(terms, l, v);
#endif
#if GONIO_HAS_MODEL(7)
    // exact lobe 0, lobes below
    if (model == MODEL_TM21) return model_belcour18_precomputed(BELCOUR_TOPLOBE, terms, l, v);
#endif
#if GONIO_HAS_MODEL(4) || GONIO_HAS_MODEL(6)
    return model_belcour18_precomputed(model - MODEL_BELCOUR18_FORWARD, terms, l, v);
#else
    return vec3(0.0f);
#endif
#else
    if (model == MODEL_TM21) return model_tm21(terms, l, v);
    return model_belcour18(model - MODEL_BELCOUR18_FORWARD, terms, l, v);
#endif
}

#ifdef BELCOUR_PRECOMPUTED_LOBES
// The lobes of Belcour's models or tm21 (whichever this module holds) at mu: the pre-passes of models.comp and
// render.comp, which store them for model_lobe(k)
GONIO_INLINE BelcourLobes model_lobes_at(float mu) {
#if GONIO_HAS_MODEL(7)
    return tm21_lobes(mu, model_use_tables());
#elif GONIO_HAS_MODEL(4) || GONIO_HAS_MODEL(5) || GONIO_HAS_MODEL(6)
    return belcour_lobes(mu, model_use_tables());
#else
    BelcourLobes b;   // no pre-pass for this model (never dispatched)
    b.count = 0u;
    b.e_t = vec3(0.0f);
    b.alpha_t = 0.0f;
    return b;
#endif
}
// Node `node` of the lobe buffer (BELCOUR_LOBE_STRIDE vec4s: the lobes (e_k, alpha_k), the transmitted lobe, the
// count in x's bits), through the includer's model_lobe_store(k, value)
GONIO_INLINE void model_store_lobes(uint node, BelcourLobes b) {
    uint o = node * BELCOUR_LOBE_STRIDE;
    for (uint k = 0u; k < MAX_LAYERS; ++k) model_lobe_store(o + k, k < b.count ? vec4(b.e[k], b.alpha[k]) : vec4(0.0f));
    model_lobe_store(o + MAX_LAYERS, vec4(b.e_t, b.alpha_t));
    model_lobe_store(o + MAX_LAYERS + 1u, vec4(uintBitsToFloat(b.count), 0.0f, 0.0f, 0.0f));
}
#endif
#endif
