// bins.glsl: the hemisphere histogram's binning and fixed-point quantisation, shared by the device and the
// CPU twin. Bins are uniform in theta (from the normal of the exit side: +z for reflection, -z for
// transmission) with edges at multiples of dtheta, and uniform in phi with bins CENTRED on multiples of
// dphi (so the plane of incidence, phi = 0 and 180 degrees, runs through the middle of a row of bins).
#ifndef GONIO_BINS_GLSL
#define GONIO_BINS_GLSL
#include "compat.glsl"

const float FIXED_SCALE = 1073741824.0f;   // 2^30: bin weights are summed as multiples of 2^-30
const float ENERGY_SCALE = 16777216.0f;    // 2^24: energy-book entries (absorbed, lost, truncated)

// Weights (0 <= w <= 1) are quantised to multiples of 2^-30, energy-book entries (|x| < 128) to multiples of
// 2^-24. The conversion goes through 32-bit integers: AVX2 has no float -> int64 instruction, and lavapipe
// would otherwise convert lane by lane (measured: 2.3x slower paths).
GONIO_INLINE uint64_t to_fixed(float w) { return uint64_t(uint(int(round(w * FIXED_SCALE)))); }
GONIO_INLINE int64_t to_fixed_energy(float x) { return int64_t(int(round(x * ENERGY_SCALE))); }

// Index of the bin (in units of bins, before the 6 values per bin) of exit direction d.
GONIO_INLINE uint bin_index(vec3 d, uint side, uint cls, uint n_theta, uint n_phi, float inv_dtheta,
                            float inv_dphi) {
    // float -> int (not uint) conversions and no integer modulo: both would run lane by lane on x86 SIMD
    float theta = atan2(sqrt(d.x * d.x + d.y * d.y), abs(d.z));
    int t = min(int(theta * inv_dtheta), int(n_theta) - 1);
    // atan(y, x) is undefined in GLSL for x = y = 0: a direction exactly along the normal is binned at phi = 0
    float phi = (d.x == 0.0f && d.y == 0.0f) ? 0.0f : atan2(d.y, d.x);   // [-pi, pi]
    int p = int(floor(phi * inv_dphi + 0.5f));                   // in [-n_phi/2, n_phi/2]
    if (p < 0) p += int(n_phi);
    if (p >= int(n_phi)) p -= int(n_phi);
    return ((cls * 2u + side) * n_theta + uint(t)) * n_phi + uint(p);
}
#endif
