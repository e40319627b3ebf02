#version 450
// simulate_batch.comp: the reference for many stacks at once (gonio sweep): simulate.comp with the stack, the
// seed and the histograms of configuration gl_WorkGroupID.y. Path for path the same walk, random numbers and
// integer sums as simulate.comp with that configuration's stack and seed, so batching changes no result.
// Each invocation traces PATHS_PER_INVOCATION light paths through the stack
// (walk.glsl) and adds every exiting path's RGB throughput, and its square, to the hemisphere histogram of
// its exit direction with 64-bit fixed-point integer atomics (packed, see bins.glsl): the sums do not depend
// on the order of the additions, so a seed gives identical bytes whatever the dispatch shape.
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

#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "bins.glsl"

layout(local_size_x = WALK_LOCAL_SIZE) in;

struct BatchStack {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;                      // x: layer count, y: histogram sides (1: opaque)
    SeriesGpu series;               // the Lambertian series (stack_params.glsl); gain.w the same for every stack
    uvec4 extra;                    // x: the configuration's seed; y: 1 while it still takes paths (--rse)
};
layout(std430, set = 0, binding = 0) readonly buffer Stacks { BatchStack stacks[]; };
uint g_config;                      // the configuration this workgroup traces
#define u_stack stacks[g_config]

// A specialised walk of one or two layers holds its configuration's layers, series and sides in these copies, read
// once per invocation (walk.glsl, walk_layer): on lavapipe every storage-buffer read is a loop over the 8 lanes, and
// the walk would repeat them on every event. The same values, so the same bits as reading them each time.
#define GONIO_HELD_STACK
const bool HELD_STACK = SPECIALISED && LAYER_COUNT <= 2u;
LayerGpu g_layer0, g_layer1;
SeriesGpu g_series;
uint g_sides;
LayerGpu held_layer(uint k) { return k == 0u ? g_layer0 : g_layer1; }
SeriesGpu held_series() { return g_series; }
uint held_sides() { return g_sides; }

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
    uint unused_seed;       // (each configuration's seed is in its stack entry)
    uint stream;            // incident-angle index
    uint max_events;
    uint n_theta;
    uint n_phi;
    float sin_ti;
    float cos_ti;
    float inv_dtheta;       // 1 / bin width in radians
    float inv_dphi;
    uint staging_stride;    // staging values per configuration
} pc;

#include "tally.glsl"

void main() {
    g_config = gl_WorkGroupID.y;
    if (stacks[g_config].extra.y == 0u) return;   // this configuration has met its --rse target
    uint seed = stacks[g_config].extra.x;
    uint staging_base = g_config * pc.staging_stride;
    uint energy_base = g_config * ENERGY_ENTRIES;
    uint first = gl_GlobalInvocationID.x * PATHS_PER_INVOCATION;
    if (HELD_STACK) {
        g_layer0 = stacks[g_config].layers[0];
        g_layer1 = stacks[g_config].layers[LAYER_COUNT - 1u];
        g_series = stacks[g_config].series;
        g_sides = uint(stacks[g_config].info.y);
    }
    Tally t;
    tally_begin(t);
    for (uint j = 0u; j < PATHS_PER_INVOCATION; ++j) {
        uint local = first + j;
        if (local >= pc.path_count) break;
        uint lo = pc.path_base_lo + local;
        uint hi = pc.path_base_hi + (lo < local ? 1u : 0u);
        Rng rng = rng_init(lo, hi, seed, pc.stream);
        PathResult r = trace_path(pc.sin_ti, pc.cos_ti, rng, pc.max_events);
        tally_path(t, r, rng, staging_base);
    }
    tally_end(t, energy_base);
}
