// simulate_head.glsl: what simulate.comp and simulate_batch.comp declare before their stack (GLSL only): the walk's
// specialisation constants, the physics, the push constants and the workgroup. The kernel then declares u_stack (and
// may bake it, walk.glsl) and includes simulate_path.glsl.
#ifndef GONIO_SIMULATE_HEAD_GLSL
#define GONIO_SIMULATE_HEAD_GLSL

#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "microsurface_walk.glsl"
#include "medium.glsl"
#include "bins.glsl"
#include "kernel_interface.glsl"

// The stack's shape specialises the walk (a two-layer stack does not pay for the general N-layer case).
layout(constant_id = SPEC_SPECIALISED) const bool SPECIALISED = true;
layout(constant_id = SPEC_LAYER_COUNT) const uint LAYER_COUNT = 2u;
layout(constant_id = SPEC_BASE_KIND) const uint BASE_KIND = 0u;
layout(constant_id = SPEC_ROUGH_MASK) const uint ROUGH_MASK = 0u;
layout(constant_id = SPEC_ABSORB_MASK) const uint ABSORB_MASK = 0u;     // media crossed by Beer-Lambert
layout(constant_id = SPEC_SCATTER_MASK) const uint SCATTER_MASK = 0u;   // media that scatter (free flights)
// interfaces whose microsurface is not GGX with height-correlated Smith (walk.glsl walk_microsurface)
layout(constant_id = SPEC_MICROSURFACE_MASK) const uint MICROSURFACE_MASK = 0u;
// interfaces where light walks on the microsurface (walk.glsl walk_multiple)
layout(constant_id = SPEC_MULTIPLE_MASK) const uint MULTIPLE_MASK = 0u;
// media of SGGX microflakes (walk.glsl walk_microflakes_any)
layout(constant_id = SPEC_MICROFLAKE_MASK) const uint MICROFLAKE_MASK = 0u;
layout(constant_id = SPEC_ORDERS) const bool ORDERS = false;        // split the histogram by path class
layout(constant_id = SPEC_PATHS_PER_INVOCATION) const uint PATHS_PER_INVOCATION = 16u;
layout(constant_id = SPEC_SERIES) const bool SERIES = false;         // the Lambertian series (walk.glsl)
layout(constant_id = SPEC_ENTRY_BRANCH) const bool ENTRY_BRANCH = false;   // the entry's both branches (trace_book.glsl)
layout(constant_id = SPEC_EXIT_ESTIMATES) const uint EXIT_ESTIMATES = 0u;  // fresh exit estimates at the base (trace_book.glsl)
// For the tests of the invalid class only: the path of this index (per incident angle, below 2^32) gets a NaN weight
// (SimOptions::invalid_path_for_tests); the default matches no path and folds away.
layout(constant_id = SPEC_INVALID_PATH_FOR_TESTS) const uint INVALID_PATH_FOR_TESTS = 0xffffffffu;
// For the negative controls of the tests only (SimOptions::fault_for_tests, FAULT_*): none by default
layout(constant_id = SPEC_FAULT_FOR_TESTS) const uint FAULT_FOR_TESTS = FAULT_NONE;
// An incident azimuth other than 0 (kernel_interface.glsl SPEC_INCIDENT_AZIMUTH)
layout(constant_id = SPEC_INCIDENT_AZIMUTH) const bool INCIDENT_AZIMUTH = false;

layout(local_size_x = WALK_LOCAL_SIZE) in;

layout(push_constant) uniform PushBlock { WalkPush pc; };
#endif
