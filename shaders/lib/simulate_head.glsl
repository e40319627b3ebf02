// simulate_head.glsl: what simulate.comp and simulate_batch.comp declare before their stack (GLSL only): the walk's
// specialisation constants, the physics, the push constants and the workgroup. The kernel then declares u_stack (and
// may bake it, walk.glsl) and includes simulate_path.glsl.
#ifndef GONIO_SIMULATE_HEAD_GLSL
#define GONIO_SIMULATE_HEAD_GLSL

// The stack's shape specialises the walk (a two-layer stack does not pay for the general N-layer case).
layout(constant_id = 0) const bool SPECIALISED = true;
layout(constant_id = 1) const uint LAYER_COUNT = 2u;
layout(constant_id = 2) const uint BASE_KIND = 0u;
layout(constant_id = 3) const uint ROUGH_MASK = 0u;
layout(constant_id = 4) const uint ABSORB_MASK = 0u;
layout(constant_id = 5) const bool ORDERS = false;        // split the histogram by path class
layout(constant_id = 6) const uint PATHS_PER_INVOCATION = 16u;
layout(constant_id = 7) const bool SERIES = false;         // the Lambertian series (walk.glsl)
// For the tests of the invalid class only: the path of this index (per incident angle, below 2^32) gets a NaN weight
// (SimOptions::invalid_path_for_tests); the default matches no path and folds away.
layout(constant_id = 47) const uint INVALID_PATH_FOR_TESTS = 0xffffffffu;

#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "bins.glsl"
#include "kernel_interface.glsl"

layout(local_size_x = WALK_LOCAL_SIZE) in;

layout(push_constant) uniform PushBlock { WalkPush pc; };
#endif
