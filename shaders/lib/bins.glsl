// bins.glsl: the hemisphere histogram's binning and fixed-point quantisation, shared by the device and the
// CPU twin. Bins are uniform in theta (from the normal of the exit side: +z for reflection, -z for
// transmission) with edges at multiples of dtheta, and uniform in phi with bins CENTRED on multiples of
// dphi (so the plane of incidence, phi = 0 and 180 degrees, runs through the middle of a row of bins).
#ifndef GONIO_BINS_GLSL
#define GONIO_BINS_GLSL
#include "compat.glsl"
#include "stack_params.glsl"   // CHANNELS

// The incident direction: light arrives at polar angle theta_i and azimuth phi_i (from x, towards y), l =
// (sin theta_i cos phi_i, sin theta_i sin phi_i, cos theta_i); at phi_i = 0 in the plane xz, which the phi bins are
// centred on. incident_direction points away from the surface (l), incident_travel the way the light travels (-l):
// its y is 0 - l.y, +0 at phi_i = 0 as (sin theta_i, 0, cos theta_i) has it, and its x -(l.x), -0 at normal
// incidence, so that phi_i = 0 gives the bits of the plane's direction.
GONIO_INLINE vec3 incident_direction(float sin_ti, float cos_ti, float sin_pi, float cos_pi) {
    return vec3(sin_ti * cos_pi, sin_ti * sin_pi, cos_ti);
}
GONIO_INLINE vec3 incident_travel(float sin_ti, float cos_ti, float sin_pi, float cos_pi) {
    return vec3(-(sin_ti * cos_pi), 0.0f - sin_ti * sin_pi, -cos_ti);
}
// The same at phi_i = 0, with a y the compiler knows is 0: the walk kernels' form for a run without an azimuth
// (simulate_head.glsl INCIDENT_AZIMUTH), and the models' (their bins are the plane's), so that their code, and its
// rounding, is that of the plane
GONIO_INLINE vec3 incident_direction_in_plane(float sin_ti, float cos_ti) { return vec3(sin_ti, 0.0f, cos_ti); }
GONIO_INLINE vec3 incident_travel_in_plane(float sin_ti, float cos_ti) { return vec3(-sin_ti, 0.0f, -cos_ti); }

// Exiting weights (0 <= w <= 1) are accumulated per dispatch in a packed staging histogram: one 64-bit atomic
// per bin and channel carries the weight (high 32 bits) and its square (low 32 bits), each quantised to
// multiples of 2^-12 with stochastic rounding (floor(x 2^12 + u), u uniform: unbiased, and its added variance,
// at most 2^-26, is far below the Monte Carlo variance). A dispatch has at most MAX_PATHS_PER_DISPATCH paths,
// so neither half can carry into the other (4096 x (2^20 - 1) < 2^32); after each dispatch, fold.comp adds
// the halves into 64-bit totals. Packing halves the atomics, which cost a third of lavapipe's time.
const float FIXED_SCALE = 4096.0f;         // 2^12
const uint MAX_PATHS_PER_DISPATCH = 1048575u;   // 2^20 - 1
const float ENERGY_SCALE = 16777216.0f;    // 2^24: energy-book entries (absorbed, lost, truncated, invalid)
// The energy book of one run: absorbed, lost, truncated, invalid, each per channel.
const uint ENERGY_ENTRIES = 4u * CHANNELS;

// floor(x 2^12 + u), computed without rounding: x 2^12 is exact (a power of two), so are its integer part i and
// fraction y - i, and the fraction carries with probability P(u < y - i) = y - i exactly (u is a multiple of
// 2^-24, and so is y - i wherever y >= 1). Adding u in float first (floor(y + u)) would round y + u to nearest
// and carry whenever u is within half an ulp of the next integer: a bias of up to 2^-24 of the weight per path,
// enough for a lossless stack to reflect and transmit 1 + 6e-8 (tests/test_hard_cases.cpp).
GONIO_INLINE uint to_fixed_dithered(float x, float u) {
    float y = x * FIXED_SCALE;
    float i = floor(y);
    return uint(int(i)) + (u < y - i ? 1u : 0u);
}

// The packed staging value of one exiting weight w, dithered by u1 (weight) and u2 (square).
GONIO_INLINE uint64_t pack_weight(float w, float u1, float u2) {
    return (uint64_t(to_fixed_dithered(w, u1)) << 32) | uint64_t(to_fixed_dithered(w * w, u2));
}

// Energy-book entries (|x| < 128): multiples of 2^-24, rounded to nearest. The conversions go through
// 32-bit integers: AVX2 has no float -> int64 (or -> uint32) instruction, and lavapipe would convert lane
// by lane (measured: 2.3x slower paths).
GONIO_INLINE int64_t to_fixed_energy(float x) { return int64_t(int(round(x * ENERGY_SCALE))); }

// Index of the bin (in units of bins, before the 6 values per bin) of exit direction d.
// n_sides: 2, or 1 for an opaque stack (no transmission bins).
GONIO_INLINE uint bin_index(vec3 d, uint side, uint cls, uint n_sides, uint n_theta, uint n_phi, float inv_dtheta,
                            float inv_dphi) {
    // float -> int (not uint) conversions and no integer modulo: both would run lane by lane on x86 SIMD
    float theta = atan2(sqrt(d.x * d.x + d.y * d.y), abs(d.z));
    int t = min(int(theta * inv_dtheta), int(n_theta) - 1);
    // atan(y, x) is undefined in GLSL for x = y = 0: a direction exactly along the normal is binned at phi = 0
    float phi = (d.x == 0.0f && d.y == 0.0f) ? 0.0f : atan2(d.y, d.x);   // [-pi, pi]
    int p = int(floor(phi * inv_dphi + 0.5f));                   // in [-n_phi/2, n_phi/2]
    if (p < 0) p += int(n_phi);
    if (p >= int(n_phi)) p -= int(n_phi);
    return ((cls * n_sides + side) * n_theta + uint(t)) * n_phi + uint(p);
}
#endif
