#version 450
// fold.comp: after each dispatch of a walk kernel, add the packed staging histogram (weight sum in the high
// 32 bits, sum of squares in the low 32 bits, per bin and channel) into the 64-bit totals and clear it.
// Each element belongs to one invocation, so no atomics are needed.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require

#include "compat.glsl"
#include "kernel_interface.glsl"

layout(local_size_x = FOLD_LOCAL_SIZE) in;

layout(std430, set = 0, binding = FOLD_BINDING_STAGING) buffer Staging { uint64_t staging[]; };
// Totals: for each bin, 3 channel sums then 3 sums of squares (units of 2^-12).
layout(std430, set = 0, binding = FOLD_BINDING_TOTALS) buffer Totals { uint64_t totals[]; };

layout(push_constant) uniform PushBlock { FoldPush pc; };   // kernel_interface.glsl

void main() {
    uint first = gl_GlobalInvocationID.x * FOLD_PER_INVOCATION;
    for (uint j = 0u; j < FOLD_PER_INVOCATION; ++j) {
        uint i = first + j;
        if (i >= pc.count) break;
        uint64_t v = staging[i];
        if (v == 0ul) continue;
        uint bin = i / 3u, c = i - bin * 3u;
        totals[bin * 6u + c] += (v >> 32) << pc.shift;
        totals[bin * 6u + 3u + c] += (v & 0xffffffffUL) << (2u * pc.shift);
        staging[i] = 0ul;
    }
}
