// model_render.h: every analytic model that can represent a stack (and each user's model file), rendered on the
// sphere under an environment on the device: environment, cosine and GGX-lobe samples combined by multiple importance
// sampling, drawn once for all the models (shaders/render_samples.comp), then each model's sums over them
// (shaders/render.comp, one pipeline per model); deterministic for a seed.
#pragma once
#include "environment.h"
#include "image.h"
#include "model_registry.h"
#include "stack.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct UserModel;   // user_model.h

struct ModelRender {
    size_t model = 0;   // registry index (a user's model: none, see user)
    const UserModel* user = nullptr;   // a user's model file (ModelOptions::user_models), else null
    uint32_t user_slot = 0;   // its place in ModelOptions::user_models
    std::string id;
    std::string not_applicable;   // non-empty: why not rendered (cannot represent the stack, not selected)
    Image image;   // RGBA, A = 1 on the sphere
    double pipeline_seconds = 0;   // host clock: creating the pipeline (lavapipe compiles the shader then)
    double render_seconds = 0;   // host clock: its dispatches (its lobe pass, its sums over the shared samples), the
        // first with its JIT
};

struct ModelRenderOptions {
    uint32_t size = 256;
    uint32_t spp = 64;   // iterations per pixel (each: one sample of each of the three strategies)
    uint32_t seed = 1;
    ModelOptions models;   // --models
};

// The stage's cost beyond each model's own (host clock).
struct ModelRenderStage {
    double setup_seconds = 0;   // Belcour's tables, E_coat, the environment's upload
    double pipelines_seconds = 0;   // every pipeline, created concurrently
    double samples_seconds = 0;   // the samples of the environment, drawn once for every model (render_samples.comp)
    uint32_t tiles = 0, tile_pixels = 0, batch_iterations = 0;   // how the samples' buffer was filled
    double wall_seconds = 0;   // the whole call
    uint32_t samples_per_dispatch = 0;
};

std::vector<ModelRender> render_models(VkContext& ctx, const Stack& s, const Environment& env,
                                       const ModelRenderOptions& o, ModelRenderStage* stage = nullptr);

}   // namespace gonio
