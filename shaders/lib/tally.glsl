// tally.glsl: booking finished paths, shared by the walk kernels and the CPU twin. Each invocation sums its paths'
// energy book in registers (tally_path) and adds it once per entry at the end (tally_end); every exiting path adds
// its RGB throughput and its square to the staging histogram, packed in 64-bit fixed-point integers (bins.glsl):
// the sums do not depend on the order of the additions, so a seed gives identical bytes whatever the dispatch shape
// or the order in which paths finish.
//
// Needs, defined by the includer: ORDERS (bool), walk.glsl (included first: walk_series, walk_sides,
// path_is_finite), and the two additions, tally_add_staging(i, packed) (staging value i, uint64_t) and
// tally_add_energy(i, v) (energy-book entry i, int64_t): 64-bit integer atomics on the device, plain additions
// into the CPU twin's per-thread sums.
#ifndef GONIO_TALLY_GLSL
#define GONIO_TALLY_GLSL

struct Tally {
    i64vec3 absorbed;
    i64vec3 lost;
    i64vec3 truncated;
    int64_t invalid;    // paths that booked a non-finite number (walk.glsl, path_is_finite), each 1 in every channel
    // the histogram's grid, read once per invocation (on lavapipe every push-constant read is an 8-lane gather)
    uint n_theta, n_phi, sides;
    float inv_dtheta, inv_dphi, weight_scale;
};

GONIO_INLINE void tally_begin(OUT(Tally) t, uint n_theta, uint n_phi, float inv_dtheta, float inv_dphi) {
    t.absorbed = i64vec3(0l);
    t.lost = i64vec3(0l);
    t.truncated = i64vec3(0l);
    t.invalid = 0l;
    t.n_theta = n_theta;
    t.n_phi = n_phi;
    t.sides = walk_sides();
    t.inv_dtheta = inv_dtheta;
    t.inv_dphi = inv_dphi;
    t.weight_scale = walk_series().gain.w;
}

GONIO_INLINE i64vec3 to_fixed_energy3(vec3 x) {
    return i64vec3(to_fixed_energy(x.x), to_fixed_energy(x.y), to_fixed_energy(x.z));
}

// The staging index (in packed values, from staging_base) of bin `bin` (bin_index's numbering).
GONIO_INLINE uint tally_staging_index(uint bin, uint staging_base) { return staging_base + bin * 3u; }

// The bin (bin_index's numbering) of an exit in direction dir on side `side` (0 reflected, 1 transmitted), class cls.
GONIO_INLINE uint tally_bin(Tally t, vec3 dir, uint side, uint cls) {
    return bin_index(dir, side, cls, t.sides, t.n_theta, t.n_phi, t.inv_dtheta, t.inv_dphi);
}

// One exit of weight w into bin `bin` of the staging histogram at staging_base: the weight and its square, packed.
// A path's exits into one bin are one exit (their sum): the bin's sum of squares is then the sum of the paths'
// squares, which its standard error needs. The dithering of the fixed-point quantisation draws from rng.
GONIO_INLINE void tally_exit(Tally t, uint bin, vec3 w, INOUT(Rng) rng, uint staging_base) {
    uint idx = tally_staging_index(bin, staging_base);
    vec4 u0 = rng_next4(rng);
    vec4 u1 = rng_next4(rng);
    vec3 ws = w * t.weight_scale;   // weights above 1 (the series): scaled by 2^-k, fold.comp
    uint64_t packed0 = pack_weight(ws.x, u0.x, u0.y), packed1 = pack_weight(ws.y, u0.z, u0.w),
             packed2 = pack_weight(ws.z, u1.x, u1.y);
    if (packed0 != 0ul) tally_add_staging(idx, packed0);
    if (packed1 != 0ul) tally_add_staging(idx + 1u, packed1);
    if (packed2 != 0ul) tally_add_staging(idx + 2u, packed2);
}

// Whether a finished path leaves the stack (and is booked in a bin), and its bin.
GONIO_INLINE bool path_leaves(PathResult r) {
    return r.outcome == OUTCOME_REFLECTED || r.outcome == OUTCOME_TRANSMITTED;
}
GONIO_INLINE uint path_bin(Tally t, PathResult r) {
    return tally_bin(t, r.dir, r.outcome == OUTCOME_TRANSMITTED ? 1u : 0u, ORDERS ? r.order : 0u);
}

// One finished path (walk_finish done): its energy book, and its exit (tally_exit) into bin `bin` (path_bin, where
// it leaves). The dithering draws from the path's own stream.
GONIO_INLINE void tally_path_at(INOUT(Tally) t, PathResult r, uint bin, INOUT(Rng) rng, uint staging_base) {
    if (!path_is_finite(r)) {
        t.invalid += int64_t(ENERGY_SCALE);
        return;
    }
    t.absorbed += to_fixed_energy3(r.absorbed);
    t.lost += to_fixed_energy3(r.lost);
    if (r.outcome == OUTCOME_TRUNCATED) t.truncated += to_fixed_energy3(r.weight);
    else if (path_leaves(r)) tally_exit(t, bin, r.weight, rng, staging_base);
}

GONIO_INLINE void tally_path(INOUT(Tally) t, PathResult r, INOUT(Rng) rng, uint staging_base) {
    tally_path_at(t, r, path_leaves(r) && path_is_finite(r) ? path_bin(t, r) : 0u, rng, staging_base);
}

// The invocation's energy book into entries energy_base + 0..11: absorbed RGB, lost RGB, truncated RGB, invalid RGB.
GONIO_INLINE void tally_end(Tally t, uint energy_base) {
    for (int c = 0; c < 3; ++c) {
        if (t.absorbed[c] != 0l) tally_add_energy(energy_base + uint(c), t.absorbed[c]);
        if (t.lost[c] != 0l) tally_add_energy(energy_base + 3u + uint(c), t.lost[c]);
        if (t.truncated[c] != 0l) tally_add_energy(energy_base + 6u + uint(c), t.truncated[c]);
        if (t.invalid != 0l) tally_add_energy(energy_base + 9u + uint(c), t.invalid);
    }
}
#endif
