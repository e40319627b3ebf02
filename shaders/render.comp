#version 450
// render.comp: one analytic model on a sphere under an environment map (gonio render; docs/RENDER.md): its pass
// sums f(w, v) x weight over the samples render_samples.comp drew for every model (each pixel's environment,
// cosine and GGX-lobe samples, their weights L cos / pdf times the power heuristic's), in the pixel's local frame.
// One module per model, as models.comp's; Belcour's and tm21's lobes come from a pass of their own first.
// The lavapipe loop limiter (65535 loop trips per invocation): a dispatch runs pc.samples iterations only, each
// 3 model evaluations (host/render/model_render.cpp keeps the product far below).
#extension GL_GOOGLE_include_directive : require

#include "compat.glsl"
#include "kernel_interface.glsl"
#include "stack_params.glsl"
#include "render_interface.glsl"

layout(local_size_x = RENDER_GROUP_SIZE) in;
// The model, as in models.comp: one module per model (GONIO_MODEL_ONLY), its conventions specialised
layout(constant_id = MODEL_SPEC_MODEL) const uint MODEL = 0u;
layout(constant_id = MODEL_SPEC_CONVENTION) const uint CONVENTION = 0u;

layout(std140, set = 0, binding = RENDER_BINDING_STACK) uniform StackBlock { StackGpu u_stack; };   // stack_params.glsl
// per model and pixel of the tile: the RGB sum over the samples so far
layout(std430, set = 0, binding = RENDER_BINDING_ACCUM) buffer Accum { vec4 accum[]; };
// the models' per-stack tables (kernel_interface.glsl STACK_TABLE_*)
layout(std430, set = 0, binding = RENDER_BINDING_STACK_TABLES) readonly buffer StackTables { float stack_tables[]; };
layout(std430, set = 0, binding = RENDER_BINDING_BELCOUR_TABLES) readonly buffer BelcourTables { float belcour_tables[]; };
// RGB radiance per texel (a user's delta lobes are lit from their direction)
layout(std430, set = 0, binding = RENDER_BINDING_ENV) readonly buffer Env { vec4 env[]; };

layout(push_constant) uniform PushBlock { RenderPush pc; };

layout(std430, set = 0, binding = RENDER_BINDING_LOBES) buffer Lobes { vec4 lobes[]; };   // the lobe pass's output

// The models' environment, as models.comp provides it. Belcour's and tm21's lobes: l changes from one evaluation to
// the next, so the lobe pass tabulates them over mu = cos theta_l at the nodes the symmetric variant's table uses,
// and every variant reads them from there (models/belcour18.glsl, BELCOUR_LOBES_OF_MU)
float model_stack_table(uint i) { return stack_tables[i]; }
uint model_parameter_slot() { return MODEL; }   // a built-in's code, a user's file's slot (the host's MODEL)
uint model_layer_count() { return stack_layer_count(u_stack.info); }
LayerGpu model_layer(uint i) { return u_stack.layers[i]; }
bool model_use_tables() { return pc.use_tables != 0u; }
float model_table(uint i) { return belcour_tables[i]; }
uint model_convention() { return CONVENTION; }
float model_mu_jump() { return pc.mu_jump; }
#define BELCOUR_PRECOMPUTED_LOBES 1
#define BELCOUR_LOBES_OF_MU 1
vec4 model_lobe(uint k) { return lobes[pc.lobes_first + k]; }   // each model's lobes in a slot of their own
void model_lobe_store(uint k, vec4 x) { lobes[pc.lobes_first + k] = x; }

#ifdef GONIO_USER_MODEL
#include "models/user_model.glsl"   // a model file compiled at run time (host/models/user_model.cpp)
#else
#include "models/all.glsl"
#endif

uint env_texel(vec3 w) { return env_texel_index(w, pc.env_w, pc.env_h); }
layout(std430, set = 0, binding = RENDER_BINDING_SAMPLES) readonly buffer Samples { vec4 samples[]; };

void main() {
#ifndef GONIO_USER_MODEL
    if (pc.pass == RENDER_PASS_LOBES) {   // the model's lobes at the nodes of mu, before the pixels' dispatches
        uint node = gl_GlobalInvocationID.x;
        if (node < BELCOUR_MU_NODES) model_store_lobes(node, model_lobes_at(belcour_mu_node(node)));
        return;
    }
#endif
    uint local = gl_GlobalInvocationID.x;
    uint pixel = pc.pixel_first + local;
    if (local >= pc.tile_pixels || pixel >= pc.size * pc.size) return;
    uint py = pixel / pc.size, px = pixel - py * pc.size;
    vec3 n;
    if (!sphere_normal(px, py, pc.size, n)) return;
    vec3 t1, t2, v;
    sphere_frame(n, t1, t2, v);
    CoatParams p = coat_params(u_stack.layers[0], u_stack.layers[1]);
    vec3 sum = vec3(0.0f);
    for (uint k = pc.first_sample; k < pc.first_sample + pc.samples; ++k)
        for (uint s = 0u; s < RENDER_STRATEGIES; ++s) {
            uint i = render_sample_index(k, s, local, pc.batch_first, pc.tile_pixels);
            vec3 weight = samples[2u * i + 1u].rgb;
            if (weight == vec3(0.0f)) continue;   // no sample, or no light from it
            sum += eval_model(MODEL, p, TERM_ALL, samples[2u * i].xyz, v) * weight;
        }
#if defined(GONIO_USER_MODEL) && defined(GONIO_MODEL_HINTS)
    // a user's delta lobes (model_lobes, roughness 0), which model_f leaves out: the light a delta sends to v comes
    // from one direction. The mirror direction of v is asked (a smooth interface's reflection); a delta it gives in
    // the direction v adds its weight times the light from there, pc.samples times (the host divides the sums by the
    // iterations). Deltas in other directions are not rendered (docs/RENDER.md).
    {
        vec3 lm = vec3(-v.x, -v.y, v.z);
        GonioLobe hl[GONIO_MAX_LOBES];   // an out parameter: only the first nh are read
        uint nh = model_lobes(lm, hl);
        vec3 w = lm.x * t1 + lm.y * t2 + lm.z * n;
        for (uint k = 0u; k < GONIO_MAX_LOBES; ++k) {
            if (k >= nh || hl[k].roughness != 0.0f || !(length(hl[k].direction) > 0.0f)) continue;
            if (dot(normalize(hl[k].direction), v) < 1.0f - 1e-6f) continue;
            sum += max(hl[k].weight, vec3(0.0f)) * env[env_texel(w)].rgb * float(pc.samples);
        }
    }
#endif
    accum[pc.accum_first + local] += vec4(sum, 0.0f);
}
