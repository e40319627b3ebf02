// rng.glsl: counter-based random numbers. A path's stream is a pure function of (seed, path index,
// incident-angle index, counter), so results do not depend on which invocation runs which path, nor on
// the dispatch shape. Generator: pcg4d (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering",
// JCGT 9(3)), applied to the 4-word counter (path_lo, path_hi, seed_mix, counter).
#ifndef GONIO_RNG_GLSL
#define GONIO_RNG_GLSL
#include "compat.glsl"

struct Rng {
    uvec4 key;    // x: path index low word, y: high word, z: seed mix, w: counter
};

GONIO_INLINE uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    v = v ^ (v >> 16u);
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    return v;
}

// The seed and stream (incident-angle index) mixed into two words through a hash, so seeds 1 and 2 do not
// produce shifted copies of each other. The same for every path of a run, so it is computed once, not per path:
// by the host for simulate.comp (a push constant), per invocation by simulate_batch.comp (one per configuration).
GONIO_INLINE uvec2 rng_seed_mix(uint seed, uint stream) {
    uvec4 s = pcg4d(uvec4(seed, stream, 0x9e3779b9u, 0x7f4a7c15u));
    return uvec2(s.x, s.y);
}

GONIO_INLINE Rng rng_init_mixed(uint path_lo, uint path_hi, uvec2 mix) {
    Rng r;
    r.key = uvec4(path_lo, path_hi, mix.x, mix.y);
    return r;
}

GONIO_INLINE Rng rng_init(uint path_lo, uint path_hi, uint seed, uint stream) {
    return rng_init_mixed(path_lo, path_hi, rng_seed_mix(seed, stream));
}

// Four uniform numbers in [0, 1) (24-bit resolution: exact in float, never 1.0). The conversion goes
// through signed int: x86 SIMD (AVX2) converts int32 to float natively, uint32 only by emulation.
GONIO_INLINE vec4 rng_next4(INOUT(Rng) r) {
    uvec4 h = pcg4d(r.key) >> 8u;
    r.key.w += 1u;
    return vec4(float(int(h.x)), float(int(h.y)), float(int(h.z)), float(int(h.w))) * (1.0f / 16777216.0f);
}
// The four numbers rng_next4 would return, without advancing the counter (the caller advances r.key.w).
GONIO_INLINE vec4 rng_peek4(Rng r) {
    uvec4 h = pcg4d(r.key) >> 8u;
    return vec4(float(int(h.x)), float(int(h.y)), float(int(h.z)), float(int(h.w))) * (1.0f / 16777216.0f);
}
#endif
