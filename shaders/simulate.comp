#version 450
// simulate.comp: the reference. Each invocation traces PATHS_PER_INVOCATION light paths through the stack
// (walk.glsl) and books them (tally.glsl): every exiting path's RGB throughput, and its square, goes to the
// hemisphere histogram of its exit direction (simulate_path.glsl). A specialised walk of one or two layers has the
// stack baked in (stack_constants.glsl); otherwise the walk reads the uniform block. Workgroup row y traces incident
// angle y of the dispatch (WalkAngle): its paths, its random streams, its histograms, so that one dispatch covers
// every angle of a run with the paths and bits of one dispatch per angle.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#include "simulate_head.glsl"
#include "stack_constants.glsl"

layout(std140, set = 0, binding = WALK_BINDING_STACK) uniform StackBlock { StackGpu u_stack; };   // stack_params.glsl
layout(std430, set = 0, binding = WALK_BINDING_ANGLES) readonly buffer Angles { WalkAngle angles[]; };   // kernel_interface.glsl

#include "simulate_path.glsl"

void main() {
    WalkAngle a = angles[gl_WorkGroupID.y];   // read once per invocation
    simulate_paths(uvec2(a.seed_mix0, a.seed_mix1), a.path_base_lo, a.path_base_hi, a.path_count,
                   INCIDENT_AZIMUTH ? incident_travel(a.sin_ti, a.cos_ti, a.sin_pi, a.cos_pi)
                                    : incident_travel_in_plane(a.sin_ti, a.cos_ti),
                   a.slot * pc.staging_stride, a.slot * ENERGY_ENTRIES);
}
