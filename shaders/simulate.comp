#version 450
// simulate.comp: the reference. Each invocation traces PATHS_PER_INVOCATION light paths through the stack
// (walk.glsl) and books them (tally.glsl): every exiting path's RGB throughput, and its square, goes to the
// hemisphere histogram of its exit direction (simulate_path.glsl). A specialised walk of one or two layers has the
// stack baked in (stack_constants.glsl); otherwise the walk reads the uniform block.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#include "simulate_head.glsl"
#include "stack_constants.glsl"

layout(std140, set = 0, binding = WALK_BINDING_STACK) uniform StackBlock { StackGpu u_stack; };   // stack_params.glsl

#include "simulate_path.glsl"

void main() {
    simulate_paths(uvec2(pc.seed_mix0, pc.seed_mix1), 0u, 0u);
}
