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
// table: test-coat-rewrite-albedo 65
//
// tests/builtin_models/99-test-coat-rewrite.glsl: a built-in model file that model_plan.cpp has no plan for, so
// that it is integrated as a black box and represents the shapes of its header (tests/builtin_model_test.sh adds
// it to a copy of shaders/lib/models/builtin/ and compiles models.comp and render.comp for it;
// tests/test_model_registry.cpp makes a registry with it). It declares a per-stack table set of its own (`table:`)
// and fills it (GONIO_MODEL_TABLES, on the host): the build lays the set out after the shipped files' and dispatches
// the hook, which builtin_model_test.sh compiles as the CPU twin does; no term reads the set.
#ifndef GONIO_TEST_COAT_REWRITE_GLSL
#define GONIO_TEST_COAT_REWRITE_GLSL
#include "models/builtin/02-ww-corrected.glsl"

GONIO_INLINE vec3 model_test_coat_rewrite(CoatParams p, uint terms, vec3 l, vec3 v) {
    return model_ww_corrected(p, TERM_TOP | TERM_BASE, l, v);
}

#ifdef __cplusplus
// test-coat-rewrite-albedo: the coat's directional albedo with G2 at the albedo sets' nodes
GONIO_INLINE void test_coat_rewrite_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_TEST_COAT_REWRITE_ALBEDO) == 0u || table_stack_shape(s) == TABLE_SHAPE_OTHER) return;
    table_store_interface_albedo(STACK_TABLE_TEST_COAT_REWRITE_ALBEDO, layer_eta(s.layers[0]), layer_alpha(s.layers[0]),
                                 FGD_G2);
}
#define GONIO_MODEL_TABLES(s, sets) test_coat_rewrite_tables(s, sets)
#endif
#endif
