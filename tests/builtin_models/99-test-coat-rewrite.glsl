// gonio-model: test-coat-rewrite
// citation: gonio's tests: ww-corrected (Bati, Pacanowski & Barla 2019, eq. 4) as a new built-in model with no
//   plan
// family: tests
// summary: the f of ww-corrected, both terms, integrated as a black box
// stacks: one dielectric coat over a Lambertian or conductor base
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: yes
// energy-conserving: yes
// variant: +g2 = convention g2: with the g2 bit set (which this model does not read)
// variant-energy-note: +g2 = as test-coat-rewrite
//
// tests/builtin_models/99-test-coat-rewrite.glsl: a built-in model file that model_plan.cpp has no plan for, so
// that it is integrated as a black box and represents the shapes of its header (tests/builtin_model_test.sh adds
// it to a copy of shaders/lib/models/builtin/ and compiles models.comp and render.comp for it;
// tests/test_model_registry.cpp makes a registry with it).
#ifndef GONIO_TEST_COAT_REWRITE_GLSL
#define GONIO_TEST_COAT_REWRITE_GLSL
#include "models/builtin/02-ww-corrected.glsl"

GONIO_INLINE vec3 model_test_coat_rewrite(CoatParams p, uint terms, vec3 l, vec3 v) {
    return model_ww_corrected(p, TERM_TOP | TERM_BASE, l, v);
}
#endif
