// tally.glsl: booking finished paths (GLSL only: buffers and 64-bit atomics). Each invocation sums its paths'
// energy book in registers (tally_path) and adds it with one atomic per entry at the end (tally_end); every
// exiting path adds its RGB throughput and its square to the staging histogram with 64-bit fixed-point integer
// atomics (packed, bins.glsl): the sums do not depend on the order of the additions, so a seed gives identical
// bytes whatever the dispatch shape or the order in which paths finish.
//
// Needs, defined by the includer: ORDERS (bool), staging[] (uint64_t), energy[] (int64_t), walk.glsl (included
// first: walk_series, walk_sides) and the push constants pc (n_theta, n_phi, inv_dtheta, inv_dphi).
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

void tally_begin(out Tally t) {
    t.absorbed = i64vec3(0l);
    t.lost = i64vec3(0l);
    t.truncated = i64vec3(0l);
    t.invalid = 0l;
    t.n_theta = pc.n_theta;
    t.n_phi = pc.n_phi;
    t.sides = walk_sides();
    t.inv_dtheta = pc.inv_dtheta;
    t.inv_dphi = pc.inv_dphi;
    t.weight_scale = walk_series().gain.w;
}

i64vec3 to_fixed_energy3(vec3 x) {
    return i64vec3(to_fixed_energy(x.x), to_fixed_energy(x.y), to_fixed_energy(x.z));
}

// One finished path (walk_finish done): its energy book, and its exit in the staging histogram at staging_base
// (in packed values). The dithering of the fixed-point quantisation draws from the path's own stream.
void tally_path(inout Tally t, PathResult r, inout Rng rng, uint staging_base) {
    if (!path_is_finite(r)) {
        t.invalid += int64_t(ENERGY_SCALE);
        return;
    }
    t.absorbed += to_fixed_energy3(r.absorbed);
    t.lost += to_fixed_energy3(r.lost);
    if (r.outcome == OUTCOME_TRUNCATED) {
        t.truncated += to_fixed_energy3(r.weight);
    } else if (r.outcome != OUTCOME_ENDED) {
        uint side = r.outcome == OUTCOME_TRANSMITTED ? 1u : 0u;
        uint cls = ORDERS ? r.order : 0u;
        uint idx = staging_base +
                   bin_index(r.dir, side, cls, t.sides, t.n_theta, t.n_phi, t.inv_dtheta, t.inv_dphi) * 3u;
        vec4 u0 = rng_next4(rng);
        vec4 u1 = rng_next4(rng);
        vec3 ws = r.weight * t.weight_scale;   // weights above 1 (the series): scaled by 2^-k, fold.comp
        uint64_t packed[3] = uint64_t[3](pack_weight(ws.x, u0.x, u0.y), pack_weight(ws.y, u0.z, u0.w),
                                         pack_weight(ws.z, u1.x, u1.y));
        for (int c = 0; c < 3; ++c)
            if (packed[c] != 0ul) atomicAdd(staging[idx + uint(c)], packed[c]);
    }
}

// The invocation's energy book into energy[energy_base + 0..11]: absorbed RGB, lost RGB, truncated RGB, invalid RGB.
void tally_end(Tally t, uint energy_base) {
    for (int c = 0; c < 3; ++c) {
        if (t.absorbed[c] != 0l) atomicAdd(energy[energy_base + uint(c)], t.absorbed[c]);
        if (t.lost[c] != 0l) atomicAdd(energy[energy_base + 3u + uint(c)], t.lost[c]);
        if (t.truncated[c] != 0l) atomicAdd(energy[energy_base + 6u + uint(c)], t.truncated[c]);
        if (t.invalid != 0l) atomicAdd(energy[energy_base + 9u + uint(c)], t.invalid);
    }
}
#endif
