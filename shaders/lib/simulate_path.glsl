// simulate_path.glsl: the paths of one invocation, traced (walk.glsl) and booked (tally.glsl), for simulate.comp and
// simulate_batch.comp (GLSL only). Needs simulate_head.glsl and the kernel's u_stack.
#ifndef GONIO_SIMULATE_PATH_GLSL
#define GONIO_SIMULATE_PATH_GLSL

#include "walk.glsl"

// Staging histogram of this dispatch: for each (class, side, theta bin, phi bin, channel) one packed value,
// weight sum (high 32 bits) and sum of squares (low 32 bits); see bins.glsl. fold.comp empties it.
layout(std430, set = 0, binding = WALK_BINDING_STAGING) buffer Staging { uint64_t staging[]; };
// Energy book: absorbed RGB, lost RGB, truncated RGB, invalid RGB (signed fixed point).
layout(std430, set = 0, binding = WALK_BINDING_ENERGY) buffer Energy { int64_t energy[]; };

void tally_add_staging(uint i, uint64_t v) { atomicAdd(staging[i], v); }
void tally_add_energy(uint i, int64_t v) { atomicAdd(energy[i], v); }

#include "tally.glsl"
#include "trace_book.glsl"

// This invocation's PATHS_PER_INVOCATION paths of the dispatch (those below path_count, numbered from base_lo/hi),
// incident along `travel` (bins.glsl incident_travel), with the random streams of seed mix `mix` (rng_seed_mix),
// booked into the staging histogram at staging_base and the energy book at energy_base. The kernel reads these once
// per invocation (on lavapipe each push-constant or buffer read is an 8-lane gather).
void simulate_paths(uvec2 mix, uint base_lo, uint base_hi, uint path_count, vec3 travel, uint staging_base,
                    uint energy_base) {
    uint first = gl_GlobalInvocationID.x * PATHS_PER_INVOCATION;
    Tally t;
    tally_begin(t, pc.n_theta, pc.n_phi, pc.inv_dtheta, pc.inv_dphi);
    uint max_events = pc.max_events;
    for (uint j = 0u; j < PATHS_PER_INVOCATION; ++j) {
        uint local = first + j;
        if (local >= path_count) break;
        uint lo = base_lo + local;
        uint hi = base_hi + (lo < local ? 1u : 0u);
        Rng rng = rng_init_mixed(lo, hi, mix);
        bool poison = INVALID_PATH_FOR_TESTS != 0xffffffffu && lo == INVALID_PATH_FOR_TESTS && hi == 0u;
        trace_and_book(travel, rng, max_events, t, staging_base, poison);
    }
    tally_end(t, energy_base);
}
#endif
