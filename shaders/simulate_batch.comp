#version 450
// simulate_batch.comp: the reference for many stacks at once (gonio sweep): simulate.comp with the stack, the
// seed and the histograms of configuration gl_WorkGroupID.y. Path for path the same walk, random numbers and
// integer sums as simulate.comp with that configuration's stack and seed (simulate_path.glsl), so batching changes
// no result.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#include "simulate_head.glsl"

layout(std430, set = 0, binding = WALK_BINDING_STACK) readonly buffer Stacks { BatchStack stacks[]; };   // kernel_interface.glsl
uint g_config;                      // the configuration this workgroup traces
#define u_stack stacks[g_config].stack

// A specialised walk of one or two layers has its configuration's layers, series and sides baked into these copies,
// read once per invocation (walk.glsl, walk_layer): on lavapipe every storage-buffer read is a loop over the 8 lanes,
// and the walk would repeat them on every event. The same values, so the same bits as reading them each time.
#define GONIO_BAKED_STACK
const bool BAKED_STACK = SPECIALISED && LAYER_COUNT <= 2u;
LayerGpu g_layer0, g_layer1;
SeriesGpu g_series;
uint g_sides;
LayerGpu baked_layer(uint k) { return k == 0u ? g_layer0 : g_layer1; }
SeriesGpu baked_series() { return g_series; }
uint baked_sides() { return g_sides; }

#include "simulate_path.glsl"

void main() {
    g_config = gl_WorkGroupID.y;
    if (stacks[g_config].extra.y == 0u) return;   // this configuration has met its --rse target
    if (BAKED_STACK) {
        g_layer0 = stacks[g_config].stack.layers[0];
        g_layer1 = stacks[g_config].stack.layers[LAYER_COUNT - 1u];
        g_series = stacks[g_config].stack.series;
        g_sides = stack_sides(stacks[g_config].stack.info);
    }
    simulate_paths(rng_seed_mix(stacks[g_config].extra.x, pc.stream), pc.path_base_lo, pc.path_base_hi, pc.path_count,
                   INCIDENT_AZIMUTH ? incident_travel(pc.sin_ti, pc.cos_ti, pc.sin_pi, pc.cos_pi)
                                    : incident_travel_in_plane(pc.sin_ti, pc.cos_ti),
                   g_config * pc.staging_stride, g_config * ENERGY_ENTRIES);
}
