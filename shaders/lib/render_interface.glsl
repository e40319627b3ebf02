// render_interface.glsl: what gonio render's host (host/render) and its kernel (shaders/render.comp) both know,
// compiled by both: the push constants, the bindings, the sphere's pixels and the environment map's convention.
#ifndef GONIO_RENDER_INTERFACE_GLSL
#define GONIO_RENDER_INTERFACE_GLSL
#include "compat.glsl"

const uint RENDER_GROUP_SIZE = 128u;   // --size at most 2048: 2048^2 / 128 = 32768 workgroups (< 65535)

const uint RENDER_BINDING_STACK = 0u;            // uniform StackBlock (as models.comp's)
const uint RENDER_BINDING_ACCUM = 1u;            // per model and pixel of a tile: the RGB sum over the samples
const uint RENDER_BINDING_STACK_TABLES = 2u;     // the models' per-stack tables (STACK_TABLE_*)
const uint RENDER_BINDING_BELCOUR_TABLES = 3u;   // FGD and TIR tables (Belcour's models, tm21)
const uint RENDER_BINDING_ENV = 4u;              // the environment's texels, RGB (vec4)
const uint RENDER_BINDING_ENV_CDF = 5u;          // its sampling CDFs (marginal over rows, then per row)
const uint RENDER_BINDING_LOBES = 6u;            // Belcour's and tm21's lobes at the nodes of mu, per model
const uint RENDER_BINDING_SAMPLES = 7u;          // the samples of the environment, shared by every model
const uint RENDER_BINDINGS = 8u;

// The passes (RenderPush::pass). The samples do not depend on the model (the strategies' densities are the
// environment's, the cosine's and the GGX lobe's at the stack's roughnesses): render_samples.comp draws them once per
// pixel and iteration, each with its weight L cos / pdf times its MIS weight, and each model's pass (render.comp)
// sums f times the weight over them.
const uint RENDER_PASS_MODEL = 0u;     // render.comp: a model's sums over the samples
const uint RENDER_PASS_LOBES = 1u;     // render.comp: the model's lobes at BELCOUR_MU_NODES nodes of mu (Belcour's, tm21)
const uint RENDER_PASS_SAMPLES = 2u;   // render_samples.comp: the samples
const uint RENDER_STRATEGIES = 3u;     // per iteration: the environment, the cosine hemisphere, the GGX lobe

struct RenderPush {
    uint size;           // pixels per side
    uint first_sample;   // this dispatch's iterations k = first_sample .. first_sample + samples - 1
    uint samples;
    uint seed;
    uint env_w;          // the environment's texels per row and rows
    uint env_h;
    uint use_tables;     // Belcour's models: 1: FGD and TIR tables
    uint env_sampled;    // 0: the environment strategy is off (a constant map: MIS compensation leaves nothing)
    float alpha_lobe0;   // the lobe strategy's roughnesses: the top interface's, and a conductor base's (or the same)
    float alpha_lobe1;
    uint pass;           // RENDER_PASS_*
    float mu_jump;       // where the lobes jump (model_mu_jump, host/models/model_plan.cpp mu_jump_of; 0: nowhere)
    uint pixel_first;    // the tile: pixels pixel_first .. pixel_first + tile_pixels - 1 (row-major)
    uint tile_pixels;
    uint batch_first;    // the first iteration the samples buffer holds
    uint accum_first;    // where the model's sums over the tile start in accum (its slot times tile_pixels)
    uint lobes_first;    // where the model's lobes start in lobes (its slot times BELCOUR_MU_NODES x BELCOUR_LOBE_STRIDE)
};

// Where sample s (RENDER_STRATEGIES per iteration) of iteration k of the tile's pixel `local` is: its direction in
// the pixel's local frame at [2 i], its weight (RGB; 0: no sample) at [2 i + 1]
GONIO_INLINE uint render_sample_index(uint k, uint s, uint local, uint batch_first, uint tile_pixels) {
    return ((k - batch_first) * RENDER_STRATEGIES + s) * tile_pixels + local;
}

// A pixel's local frame: z = n, x towards the viewer v = +z (the plane of incidence of the view, phi = 0), y = z x x;
// v in that frame
GONIO_INLINE void sphere_frame(vec3 n, OUT(vec3) t1, OUT(vec3) t2, OUT(vec3) v) {
    t1 = vec3(-n.x * n.z, -n.y * n.z, 1.0f - n.z * n.z);
    float tl = length(t1);
    t1 = tl > 1e-6f ? t1 / tl : vec3(1.0f, 0.0f, 0.0f);
    t2 = cross(n, t1);
    v = vec3(t1.z, 0.0f, n.z);
}

// The sphere: pixel (px, py) of a size x size frame, row 0 at the top, covers x in [-1, 1] left to right and y in
// [1, -1] top to bottom; its centre is on the unit sphere when x^2 + y^2 < 1, with normal n = (x, y, sqrt(1 - r^2)).
GONIO_INLINE bool sphere_normal(uint px, uint py, uint size, OUT(vec3) n) {
    float x = (2.0f * (float(px) + 0.5f)) / float(size) - 1.0f;
    float y = 1.0f - (2.0f * (float(py) + 0.5f)) / float(size);
    float r2 = x * x + y * y;
    n = vec3(x, y, sqrt(max(1.0f - r2, 0.0f)));
    return r2 < 1.0f;
}

// The environment map's convention (equirectangular, z up): u = phi / (2 pi) with phi = atan2(y, x) in [0, 2 pi)
// from +x towards +y, v = theta / pi with theta the angle from +z (row 0 is the zenith, the middle row the
// horizon z = 0, the last row the nadir).
GONIO_INLINE vec2 env_uv(vec3 w) {
    float phi = atan2(w.y, w.x);
    if (phi < 0.0f) phi += 2.0f * PI;
    float u = phi * (0.5f / PI);
    float v = acos(clamp(w.z, -1.0f, 1.0f)) * (1.0f / PI);
    vec2 uv;
    uv.x = min(u, 0.99999994f);
    uv.y = min(v, 0.99999994f);
    return uv;
}
// The texel of direction w in a map of env_w x env_h texels, row-major
GONIO_INLINE uint env_texel_index(vec3 w, uint env_w, uint env_h) {
    vec2 uv = env_uv(w);
    uint i = min(uint(uv.x * float(env_w)), env_w - 1u), j = min(uint(uv.y * float(env_h)), env_h - 1u);
    return j * env_w + i;
}
GONIO_INLINE vec3 env_direction(vec2 uv) {
    float phi = 2.0f * PI * uv.x, theta = PI * uv.y;
    float s = sin(theta);
    return vec3(s * cos(phi), s * sin(phi), cos(theta));
}
#endif
