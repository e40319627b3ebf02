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
#ifdef BELCOUR_PRECOMPUTED_LOBES
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
#endif
