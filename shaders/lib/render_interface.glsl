// render_interface.glsl: what gonio render's host (host/render) and its kernel (shaders/render.comp) both know,
// compiled by both: the push constants, the bindings, the sphere's pixels and the environment map's convention.
#ifndef GONIO_RENDER_INTERFACE_GLSL
#define GONIO_RENDER_INTERFACE_GLSL
#include "compat.glsl"

const uint RENDER_GROUP_SIZE = 128u;   // --size at most 2048: 2048^2 / 128 = 32768 workgroups (< 65535)

const uint RENDER_BINDING_STACK = 0u;            // uniform StackBlock (as models.comp's)
const uint RENDER_BINDING_ACCUM = 1u;            // per pixel: the RGB sum over the samples so far
const uint RENDER_BINDING_COAT_ALBEDO = 2u;      // E_coat(mu) (albedo-scaling)
const uint RENDER_BINDING_BELCOUR_TABLES = 3u;   // FGD and TIR tables (Belcour's models, tm21)
const uint RENDER_BINDING_ENV = 4u;              // the environment's texels, RGB (vec4)
const uint RENDER_BINDING_ENV_CDF = 5u;          // its sampling CDFs (marginal over rows, then per row)
const uint RENDER_BINDING_LOBES = 6u;            // Belcour's and tm21's lobes at the nodes of mu (the lobe pass)
const uint RENDER_BINDINGS = 7u;

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
    uint lobe_pass;      // 1: the pre-pass, the model's lobes at BELCOUR_MU_NODES nodes of mu (Belcour's, tm21)
    float mu_jump;       // where the lobes jump (model_mu_jump, host/models/model_plan.cpp mu_jump_of; 0: nowhere)
};

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
GONIO_INLINE vec3 env_direction(vec2 uv) {
    float phi = 2.0f * PI * uv.x, theta = PI * uv.y;
    float s = sin(theta);
    return vec3(s * cos(phi), s * sin(phi), cos(theta));
}
#endif
