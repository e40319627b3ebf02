// models/all.glsl: every analytic model, by index (the order of host/models.cpp's registry).
#ifndef GONIO_MODELS_ALL_GLSL
#define GONIO_MODELS_ALL_GLSL
#include "ww09.glsl"
#include "elek10.glsl"
#include "ww_corrected.glsl"
#include "albedo_scaling.glsl"

const uint MODEL_WW09 = 0u;
const uint MODEL_ELEK10 = 1u;
const uint MODEL_WW_CORRECTED = 2u;
const uint MODEL_ALBEDO_SCALING = 3u;

GONIO_INLINE vec3 eval_model(uint model, CoatParams p, uint terms, vec3 l, vec3 v) {
    if (model == MODEL_WW09) return model_ww09(p, terms, l, v);
    if (model == MODEL_ELEK10) return model_elek10(p, terms, l, v);
    if (model == MODEL_WW_CORRECTED) return model_ww_corrected(p, terms, l, v);
    return model_albedo_scaling(p, terms, l, v);
}
#endif
