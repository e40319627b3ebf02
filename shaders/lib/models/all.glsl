// models/all.glsl: every built-in model, by code. A built-in model is one file, shaders/lib/models/builtin/NN-ID.glsl:
// its header (host/models/model_file.h: id, citation, summary, stacks, represents, claims, variants) is what the
// registry is read from (host/models/model_registry.cpp, the same files embedded in the binary), and it defines its
// entry   vec3 model_ID(CoatParams p, uint terms, vec3 l, vec3 v)   (ID with - . + as _). Its code is its place
// among the folder's files by name (the registry's order). CMakeLists.txt compiles models.comp and render.comp once
// per file and generates builtin_models.glsl (cmake/builtin_models.cmake): each file's #include and eval_model's
// dispatch to its entry. Two-layer models take the two-layer CoatParams; Belcour's and tm21 read the whole stack
// through model_layer().
// A file may define hooks for models.comp's kernels (only the module of its own code sees them):
//   GONIO_MODEL_LOBES(mu, tables): the pre-pass (KERNEL 2) that computes its lobes once per dispatch;
//   GONIO_MODEL_LOBE_TABLE: that pre-pass tabulates them at BELCOUR_MU_NODES nodes of mu, not at cos theta_i only;
//   GONIO_MODEL_EXACT(terms, l, v): what bins next to the lobes' jump at mu_jump evaluate instead of the entry.
//   GONIO_MODEL_BASE_ALPHA(p): for a `plan: coat` model whose coat roughens its base (openpbr), the roughness its base
//   lobe has; the CPU twin's plan grades that term at it (host/models/model_plan.cpp), else at the base's own.
//   GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a): a production model's mapping from the stack to what an artist sets
//   in it, the values of its header's `artist-parameters:` line for the stack's shape (models/common.glsl
//   ArtistValues); the CPU twin runs it (`gonio models STACK`, host/models/artist_parameters.cpp).
// render.comp (BELCOUR_LOBES_OF_MU) runs the GONIO_MODEL_LOBES pre-pass at the BELCOUR_MU_NODES nodes for every such
// model, since l changes from one evaluation to the next: the entry then reads its lobes at mu = cos theta_l
// (model_belcour18_lobes_of_mu) or |h.l| (the symmetric variant's table).
// The includer provides the model environment (models.comp, render.comp; host/models/model_twin.h for the CPU twin).
#ifndef GONIO_MODELS_ALL_GLSL
#define GONIO_MODELS_ALL_GLSL
// GONIO_MODEL_ONLY (models.comp and render.comp, one SPIR-V module per model, CMakeLists.txt): only that model's
// file is included, so the module holds one model's code, and lavapipe translates and optimises one model per
// pipeline, not all of them (with all eight, pipeline creation took most of the model stage's wall time)
#ifdef GONIO_MODEL_ONLY
#define GONIO_HAS_MODEL(i) (GONIO_MODEL_ONLY == (i))
#else
#define GONIO_HAS_MODEL(i) 1
#endif
#include "models/common.glsl"
#include "models/stack_tables.glsl"   // the per-stack tables, through the includer's model_stack_table(i)
#include "builtin_models.glsl"   // generated into the build folder (cmake/builtin_models.cmake)

#ifdef BELCOUR_PRECOMPUTED_LOBES
#include "models/belcour18.glsl"   // BelcourLobes, for every model's module
// The lobes of the module's model at mu (its GONIO_MODEL_LOBES hook): the pre-passes of models.comp (KERNEL 2) and
// render.comp (the lobe pass), which store them for model_lobe(k)
GONIO_INLINE BelcourLobes model_lobes_at(float mu) {
#ifdef GONIO_MODEL_LOBES
    return GONIO_MODEL_LOBES(mu, model_use_tables());
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
