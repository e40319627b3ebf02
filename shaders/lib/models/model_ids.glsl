// models/model_ids.glsl: the built-in models' code, by index (the order of host/models/model_registry.cpp's
// registry), and which of them a SPIR-V module holds.
#ifndef GONIO_MODEL_IDS_GLSL
#define GONIO_MODEL_IDS_GLSL
const uint MODEL_WW09 = 0u;
const uint MODEL_ELEK10 = 1u;
const uint MODEL_WW_CORRECTED = 2u;
const uint MODEL_ALBEDO_SCALING = 3u;
const uint MODEL_BELCOUR18_FORWARD = 4u;
const uint MODEL_BELCOUR18_SYMMETRIC = 5u;
const uint MODEL_BELCOUR18_TOPLOBE = 6u;
const uint MODEL_TM21 = 7u;

// GONIO_MODEL_ONLY (models.comp, one SPIR-V module per model, CMakeLists.txt): only that model's code is
// reachable, so glslang leaves the others out of the module and lavapipe translates and optimises one model per
// pipeline, not all eight (with all eight, pipeline creation takes most of the model stage's wall time).
#ifdef GONIO_MODEL_ONLY
#define GONIO_HAS_MODEL(i) (GONIO_MODEL_ONLY == (i))
#else
#define GONIO_HAS_MODEL(i) 1
#endif
#endif
