#version 450
// simulate.comp: the reference. Each invocation traces PATHS_PER_INVOCATION light paths through the stack
// (walk.glsl) and books them (tally.glsl): every exiting path's RGB throughput, and its square, goes to the
// hemisphere histogram of its exit direction. A specialised walk of one or two layers has the stack compiled in
// (stack_constants.glsl); otherwise the walk reads the uniform block.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

// The stack's shape specialises the walk (a two-layer stack does not pay for the general N-layer case).
layout(constant_id = 0) const bool SPECIALISED = true;
layout(constant_id = 1) const uint LAYER_COUNT = 2u;
layout(constant_id = 2) const uint BASE_KIND = 0u;
layout(constant_id = 3) const uint ROUGH_MASK = 0u;
layout(constant_id = 4) const uint ABSORB_MASK = 0u;
layout(constant_id = 5) const bool ORDERS = false;        // split the histogram by path class
layout(constant_id = 6) const uint PATHS_PER_INVOCATION = 16u;
layout(constant_id = 7) const bool SERIES = false;         // the Lambertian series (walk.glsl)
// For the tests of the invalid class only: the path of this index (per incident angle, below 2^32) gets a NaN weight
// (SimOptions::invalid_path_for_tests); the default matches no path and folds away.
layout(constant_id = 47) const uint INVALID_PATH_FOR_TESTS = 0xffffffffu;

#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "bins.glsl"
#include "stack_constants.glsl"

layout(local_size_x = WALK_LOCAL_SIZE) in;

layout(std140, set = 0, binding = 0) uniform StackBlock {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;                      // x: layer count, y: histogram sides (1: opaque)
    SeriesGpu series;               // the Lambertian series (stack_params.glsl)
} u_stack;

#include "walk.glsl"

// Staging histogram of this dispatch: for each (class, side, theta bin, phi bin, channel) one packed value,
// weight sum (high 32 bits) and sum of squares (low 32 bits); see bins.glsl. fold.comp empties it.
layout(std430, set = 0, binding = 1) buffer Staging { uint64_t staging[]; };
// Energy book: absorbed RGB, lost RGB, truncated RGB, invalid RGB (signed fixed point).
layout(std430, set = 0, binding = 2) buffer Energy { int64_t energy[]; };

layout(push_constant) uniform Push {
    uint path_base_lo;      // first path index of this dispatch (64-bit)
    uint path_base_hi;
    uint path_count;        // paths in this dispatch
    uint seed_mix0;         // rng_seed_mix(seed, stream = incident-angle index), computed by the host
    uint seed_mix1;
    uint max_events;
    uint n_theta;
    uint n_phi;
    float sin_ti;
    float cos_ti;
    float inv_dtheta;       // 1 / bin width in radians
    float inv_dphi;
} pc;

#include "tally.glsl"

void main() {
    uint first = gl_GlobalInvocationID.x * PATHS_PER_INVOCATION;
    Tally t;
    tally_begin(t);
    // the push constants, read once (on lavapipe each read is an 8-lane gather)
    uint path_count = pc.path_count, base_lo = pc.path_base_lo, base_hi = pc.path_base_hi, max_events = pc.max_events;
    uvec2 mix = uvec2(pc.seed_mix0, pc.seed_mix1);
    float sin_ti = pc.sin_ti, cos_ti = pc.cos_ti;
    for (uint j = 0u; j < PATHS_PER_INVOCATION; ++j) {
        uint local = first + j;
        if (local >= path_count) break;
        uint lo = base_lo + local;
        uint hi = base_hi + (lo < local ? 1u : 0u);
        Rng rng = rng_init_mixed(lo, hi, mix);
        PathResult r = trace_path(sin_ti, cos_ti, rng, max_events);
        if (INVALID_PATH_FOR_TESTS != 0xffffffffu && lo == INVALID_PATH_FOR_TESTS && hi == 0u) r.weight.x = uintBitsToFloat(0x7fc00000u);
        tally_path(t, r, rng, 0u);
    }
    tally_end(t, 0u);
}
