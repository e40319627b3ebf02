// kernel_interface.glsl: everything the host and the compute kernels both know, compiled as GLSL by the kernels
// and as C++ (through compat.glsl and GLM) by the host: push-constant structs, workgroup sizes, fixed-point scales,
// table sizes, node rules. A value the two sides share is written here once, never mirrored by hand.
// A kernel declares its push constants as a block holding one of these structs:
//     layout(push_constant) uniform PushBlock { WalkPush pc; };
// and the host fills the same struct (static_assert on its size beside the struct).
#ifndef GONIO_KERNEL_INTERFACE_GLSL
#define GONIO_KERNEL_INTERFACE_GLSL
#include "compat.glsl"

// ---- the walk kernels (simulate.comp, simulate_batch.comp, fold.comp) ----
#include "stack_params.glsl"   // BatchStack's StackGpu

// The workgroup shapes the kernels declare and the hosts dispatch by (host/reference/walk_runner.h,
// host/gpu/fold_kernel.cpp).
const uint WALK_LOCAL_SIZE = 64u;       // invocations per workgroup of simulate.comp and simulate_batch.comp
const uint FOLD_LOCAL_SIZE = 64u;       // of fold.comp
const uint FOLD_PER_INVOCATION = 16u;   // staging elements each fold.comp invocation adds

// The walk kernels' specialisation constant ids (simulate_head.glsl, stack_constants.glsl), which build_walk_kernel
// (host/gpu/compute_kernel.h) sets.
const uint SPEC_SPECIALISED = 0u;
const uint SPEC_LAYER_COUNT = 1u;
const uint SPEC_BASE_KIND = 2u;
const uint SPEC_ROUGH_MASK = 3u;
const uint SPEC_ABSORB_MASK = 4u;
const uint SPEC_ORDERS = 5u;
const uint SPEC_PATHS_PER_INVOCATION = 6u;
const uint SPEC_SERIES = 7u;
const uint SPEC_BAKED_STACK = 8u;              // simulate.comp: the baked stack
const uint SPEC_BAKED_SIDES = 9u;
const uint SPEC_BAKED_LAYERS = 10u;            // layers[0], layers[1]: p0.xyzw, tau.xyz, c0.xyz, c1.xyz each
const uint BAKED_LAYER_FLOATS = 13u;
const uint SPEC_BAKED_SERIES = 36u;            // series: gain.xyzw, lost.xyz, emit.xyzw
const uint BAKED_SERIES_FLOATS = 11u;
const uint SPEC_INVALID_PATH_FOR_TESTS = 47u;

// The push constants of simulate.comp and simulate_batch.comp: one dispatch's paths, the incident direction and
// the histogram's grid.
struct WalkPush {
    uint path_base_lo;      // first path index of this dispatch (64-bit)
    uint path_base_hi;
    uint path_count;        // paths in this dispatch (per configuration)
    uint seed_mix0;         // simulate.comp: rng_seed_mix(seed, stream), computed once by the host
    uint seed_mix1;
    uint stream;            // incident-angle index (simulate_batch.comp mixes it with each configuration's seed)
    uint max_events;
    uint n_theta;
    uint n_phi;
    float sin_ti;
    float cos_ti;
    float inv_dtheta;       // 1 / bin width in radians
    float inv_dphi;
    uint staging_stride;    // simulate_batch.comp: staging values per configuration
};

// One configuration of simulate_batch.comp (std430, the storage buffer Stacks): its stack as the walk reads it and
// its own seed and state.
struct BatchStack {
    StackGpu stack;                 // stack_params.glsl; series.gain.w the same for every stack of a batch
    uvec4 extra;                    // x: the configuration's seed; y: 1 while it still takes paths (--rse)
};

// fold.comp's push constants. count: staging elements (bins x 3 channels). shift: the staging holds weights times
// 2^-shift (a walk whose weights exceed 1, the Lambertian series): the totals stay in units of 2^-12.
struct FoldPush {
    uint count;
    uint shift;
};

#ifdef __cplusplus
static_assert(SPEC_BAKED_LAYERS + 2u * BAKED_LAYER_FLOATS == SPEC_BAKED_SERIES &&
              SPEC_BAKED_SERIES + BAKED_SERIES_FLOATS <= SPEC_INVALID_PATH_FOR_TESTS, "specialisation constant ids");
static_assert(sizeof(WalkPush) == 56 && sizeof(FoldPush) == 8, "push-constant layout (std430, scalars only)");
static_assert(sizeof(BatchStack) == 64 * MAX_LAYERS + 80, "std430 layout (vec4 members only)");
#endif

// ---- the model kernels (models.comp, belcour_tables.comp, ...) ----

#endif
