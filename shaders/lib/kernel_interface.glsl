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

// ---- the model kernels (models.comp, belcour_tables.comp, ...) ----

#endif
