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
#include "builtin_models.glsl"   // generated into the build folder (cmake/builtin_models.cmake)
#endif
