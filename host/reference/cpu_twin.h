// cpu_twin.h: the reference walk on the CPU, compiled from the very same shader sources (shaders/lib/*.glsl)
// through GLM. Used by the unit tests (physics of single events, sampling densities) and by `gonio bench`.
#pragma once
#include "compat.glsl"
#include "rng.glsl"
#include "stack_params.glsl"
#include "interface.glsl"
#include "bins.glsl"

#include <cstdint>
#include <vector>

namespace gonio {

// Same layout as the shader's uniform block StackBlock.
struct StackGpu {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;   // x: layer count, y: histogram sides (2, or 1 for an opaque stack)
    SeriesGpu series;   // the Lambertian series (stack_params.glsl; pack_walk_stack fills it)
};
static_assert(sizeof(LayerGpu) == 64 && sizeof(SeriesGpu) == 48 && sizeof(StackGpu) == 64 * MAX_LAYERS + 64, "std140 layout");

// The walk's specialisation, the values of the shader's specialisation constants.
struct WalkSpec {
    bool specialised = true;
    uint layer_count = 1, base_kind = 0, rough_mask = 0, absorb_mask = 0;
    bool series = false;     // the Lambertian series (walk.glsl; lambertian_series.h)
};

// walk.glsl compiled as member functions: the shader's specialisation constants and uniform block
// become members of the same names.
struct CpuWalker {
    bool SPECIALISED, SERIES;
    uint LAYER_COUNT, BASE_KIND, ROUGH_MASK, ABSORB_MASK;
    StackGpu u_stack;

    CpuWalker(const StackGpu& stack, const WalkSpec& spec)
        : SPECIALISED(spec.specialised), SERIES(spec.series), LAYER_COUNT(spec.layer_count), BASE_KIND(spec.base_kind),
          ROUGH_MASK(spec.rough_mask), ABSORB_MASK(spec.absorb_mask), u_stack(stack) {}

#include "walk.glsl"
};

}  // namespace gonio
