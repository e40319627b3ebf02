// cpu_twin.h: the reference walk on the CPU, compiled from the very same shader sources (shaders/lib/*.glsl)
// through GLM. Used by the unit tests (physics of single events, sampling densities) and by `gonio bench`.
#pragma once
#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "microsurface_walk.glsl"
#include "medium.glsl"
#include "bins.glsl"
#include "kernel_interface.glsl"   // FAULT_*
#include "incidence.h"
#include "stack_gpu.h"   // WalkSpec

#include <cstdint>
#include <vector>

#include <glm/gtc/type_precision.hpp>

namespace gonio {

using glm::i64vec3;   // tally.glsl

// The incident light's direction of travel, as the kernels build it (incidence.h, bins.glsl incident_travel)
inline vec3 incident_travel_of(double theta_i_deg, double phi_i_deg) {
    const IncidentTrig t = incident_trig(theta_i_deg, phi_i_deg);
    return incident_travel(t.sin_ti, t.cos_ti, t.sin_pi, t.cos_pi);
}

// walk.glsl compiled as member functions: the shader's specialisation constants and uniform block
// become members of the same names.
struct CpuWalker {
    bool SPECIALISED, SERIES, ENTRY_BRANCH;
    uint EXIT_ESTIMATES, LAYER_COUNT, BASE_KIND, ROUGH_MASK, ABSORB_MASK, SCATTER_MASK, MICROSURFACE_MASK,
        MULTIPLE_MASK, MICROFLAKE_MASK;
    StackGpu u_stack;

    CpuWalker(const StackGpu& stack, const WalkSpec& spec)
        : SPECIALISED(spec.specialised),
          SERIES(spec.series),
          ENTRY_BRANCH(spec.entry_branch),
          EXIT_ESTIMATES(spec.exit_estimates),
          LAYER_COUNT(spec.layer_count),
          BASE_KIND(spec.base_kind),
          ROUGH_MASK(spec.rough_mask),
          ABSORB_MASK(spec.absorb_mask),
          SCATTER_MASK(spec.scatter_mask),
          MICROSURFACE_MASK(spec.microsurface_mask),
          MULTIPLE_MASK(spec.multiple_mask),
          MICROFLAKE_MASK(spec.microflake_mask),
          u_stack(stack) {}

#include "walk.glsl"
};

// The walk and tally.glsl's booking, as simulate.comp runs them, into one thread's 64-bit sums: `totals` in the
// layout of fold.comp's totals (per bin 3 channel sums, then 3 sums of squares) and the energy book. The staging
// scale is 1 (no packed staging to keep from carrying: each packed value is added at once, as fold.comp adds it).
struct CpuTwin : CpuWalker {
    bool ORDERS;
    uint FAULT_FOR_TESTS = FAULT_NONE;   // the GPU's alone carry the tests' faults
    uint64_t* totals;
    int64_t* energy;

    CpuTwin(const StackGpu& stack, const WalkSpec& spec, bool orders, uint64_t* totals_, int64_t* energy_)
        : CpuWalker(stack, spec), ORDERS(orders), totals(totals_), energy(energy_) {
        u_stack.series.gain.w = 1.0f;   // the weight scale; the walk reads only gain.xyz
    }
    void tally_add_staging(uint i, uint64_t v) {   // as fold.comp with shift 0
        uint bin = i / 3u, c = i - bin * 3u;
        totals[bin * 6u + c] += v >> 32;
        totals[bin * 6u + 3u + c] += v & 0xffffffffull;
    }
    void tally_add_energy(uint i, int64_t v) { energy[i] += v; }

#include "tally.glsl"
#include "trace_book.glsl"
};

}   // namespace gonio
