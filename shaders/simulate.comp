#version 450
// simulate.comp: the reference. Each invocation traces PATHS_PER_INVOCATION light paths through the stack
// (walk.glsl) and adds every exiting path's RGB throughput, and its square, to the hemisphere histogram of
// its exit direction with 64-bit fixed-point integer atomics (packed, see bins.glsl): the sums do not depend
// on the order of the additions, so a seed gives identical bytes whatever the dispatch shape.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

layout(local_size_x = 64) in;

// The stack's shape specialises the walk (a two-layer stack does not pay for the general N-layer case).
layout(constant_id = 0) const bool SPECIALISED = true;
layout(constant_id = 1) const uint LAYER_COUNT = 2u;
layout(constant_id = 2) const uint BASE_KIND = 0u;
layout(constant_id = 3) const uint ROUGH_MASK = 0u;
layout(constant_id = 4) const uint ABSORB_MASK = 0u;
layout(constant_id = 5) const bool ORDERS = false;        // split the histogram by path class
layout(constant_id = 6) const uint PATHS_PER_INVOCATION = 16u;
layout(constant_id = 7) const bool SERIES = false;         // the Lambertian series (walk.glsl)

#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "bins.glsl"

layout(std140, set = 0, binding = 0) uniform StackBlock {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;                      // x: layer count, y: histogram sides (1: opaque)
    SeriesGpu series;               // the Lambertian series (stack_params.glsl)
} u_stack;

#include "walk.glsl"

// Staging histogram of this dispatch: for each (class, side, theta bin, phi bin, channel) one packed value,
// weight sum (high 32 bits) and sum of squares (low 32 bits); see bins.glsl. fold.comp empties it.
layout(std430, set = 0, binding = 1) buffer Staging { uint64_t staging[]; };
// Energy book: absorbed RGB, lost RGB, truncated RGB (signed fixed point).
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


void main() {
    uint first = gl_GlobalInvocationID.x * PATHS_PER_INVOCATION;
    int64_t e_abs[3] = int64_t[3](0l, 0l, 0l);
    int64_t e_lost[3] = int64_t[3](0l, 0l, 0l);
    int64_t e_trunc[3] = int64_t[3](0l, 0l, 0l);
    for (uint j = 0u; j < PATHS_PER_INVOCATION; ++j) {
        uint local = first + j;
        if (local >= pc.path_count) break;
        uint lo = pc.path_base_lo + local;
        uint hi = pc.path_base_hi + (lo < local ? 1u : 0u);
        Rng rng = rng_init_mixed(lo, hi, uvec2(pc.seed_mix0, pc.seed_mix1));
        PathResult r = trace_path(pc.sin_ti, pc.cos_ti, rng, pc.max_events);
        for (int c = 0; c < 3; ++c) {
            e_abs[c] += to_fixed_energy(r.absorbed[c]);
            e_lost[c] += to_fixed_energy(r.lost[c]);
        }
        if (r.outcome == OUTCOME_TRUNCATED) {
            for (int c = 0; c < 3; ++c) e_trunc[c] += to_fixed_energy(r.weight[c]);
        } else if (r.outcome != OUTCOME_ENDED) {
            uint side = r.outcome == OUTCOME_TRANSMITTED ? 1u : 0u;
            uint cls = ORDERS ? r.order : 0u;
            uint idx = bin_index(r.dir, side, cls, uint(u_stack.info.y), pc.n_theta, pc.n_phi, pc.inv_dtheta, pc.inv_dphi) * 3u;
            vec4 u0 = rng_next4(rng);
            vec4 u1 = rng_next4(rng);
            vec3 ws = r.weight * u_stack.series.gain.w;   // weights above 1 (the series): scaled by 2^-k, fold.comp
            uint64_t packed[3] = uint64_t[3](pack_weight(ws.x, u0.x, u0.y), pack_weight(ws.y, u0.z, u0.w),
                                             pack_weight(ws.z, u1.x, u1.y));
            for (int c = 0; c < 3; ++c)
                if (packed[c] != 0ul) atomicAdd(staging[idx + uint(c)], packed[c]);
        }
    }
    for (int c = 0; c < 3; ++c) {
        if (e_abs[c] != 0l) atomicAdd(energy[c], e_abs[c]);
        if (e_lost[c] != 0l) atomicAdd(energy[3 + c], e_lost[c]);
        if (e_trunc[c] != 0l) atomicAdd(energy[6 + c], e_trunc[c]);
    }
}
