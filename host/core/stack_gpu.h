// stack_gpu.h: a parsed Stack turned into what the walk reads (uniform block and specialisation).
#pragma once
#include "compat.glsl"
#include "stack_params.glsl"
#include "lambertian_series.h"
#include "stack.h"

namespace gonio {

using ::StackGpu;   // stack_params.glsl

// The walk's specialisation, the values of the shader's specialisation constants.
struct WalkSpec {
    bool specialised = true;
    uint layer_count = 1, base_kind = 0, rough_mask = 0;
    uint absorb_mask = 0;   // media crossed by Beer-Lambert (optical depth > 0, nothing scatters)
    uint scatter_mask = 0;   // media that scatter (free flights, walk.glsl); for the general walk (specialised false)
        // only whether it is 0 counts: whether the walk carries the free-flight code
    uint microsurface_mask = 0;   // rough interfaces' microsurfaces other than GGX with height-correlated Smith,
        // MICROSURFACE_BITS per interface (microsurface.glsl); for the general walk only whether it is 0 counts
    uint multiple_mask = 0;   // rough interfaces where light walks on the microsurface (`microfacets = "multiple"`),
        // a bit per interface; for the general walk only whether it is 0 counts
    uint microflake_mask = 0;   // media of SGGX microflakes (`phase = "sggx-fibre"` or `"sggx-flake"`), a bit per
        // medium; for the general walk only whether it is 0 counts
    bool series = false;   // the Lambertian series (walk.glsl; lambertian_series.h)
    bool entry_branch = false;   // the entry's both branches (trace_book.glsl)
    uint32_t exit_estimates = 0;   // fresh exit estimates at the base per path, to MAX_EXIT_ESTIMATES (trace_book.glsl)
    bool operator==(const WalkSpec&) const = default;
};

// The stack's layers (what the models read too); series: off (gain 0, weight scale 1).
StackGpu pack_stack(const Stack& s);

// A rough interface's microsurface as the walk reads it (microsurface.glsl MICROSURFACE_*); 0 where it is smooth or
// GGX with height-correlated Smith and single scattering (every stack that sets none of the microsurface keys).
uint layer_microsurface_code(const Layer& L);

// The walk's specialisation alone. specialised = false gives the general N-layer walk (everything read from the
// uniform block). The Lambertian series (lambertian_series.h) is on where it applies, the walk is specialised,
// `series` allows it, the histogram is not split by path class (`orders`: the series sums the classes) and
// max_events leaves room for its 3 events.
// branching: the booking estimators where they apply (trace_book.glsl; false: the analog walk, one branch per event).
WalkSpec walk_spec(const Stack& s, bool specialised, bool series = true, bool orders = false, uint32_t max_events = 256,
                   bool branching = true);

// Whether a walk of this specialisation can have a baked stack: its parameters compiled into the pipeline as
// specialisation constants (shaders/lib/stack_constants.glsl; simulate_batch.comp copies them once per
// invocation). A specialised walk of at most two layers, whose layer indices are then all compile-time
// constants; the general walk, longer stacks and stacks whose media scatter (whose medium reads take a per-lane
// layer index) read the uniform block.
bool can_bake_stack(const WalkSpec& ws);

// Everything a stack implies for the walk, derived once (the series' quadrature included) and passed to the
// kernels' hosts and the CPU twin.
struct WalkStack {
    WalkSpec spec;   // the specialisation constants
    LambertianSeries series;   // the series' terms, or why it does not apply (whether or not the walk runs it)
    StackGpu gpu;   // what the walk reads: pack_stack and, where spec.series, the series' terms;
        // gpu.series.gain.w = 2^-staging_shift (fold.comp)
    int weight_shift = 0;   // the staging scale this stack needs: weights up to 2^shift (0 unless the series is on)
    int staging_shift = 0;   // the staging scale it runs with: weight_shift, or a batch's common one

    // A batch's stacks share one staging scale, the largest any of them needs: sets it (at least weight_shift).
    void set_staging_shift(int shift);
};
WalkStack walk_stack(const Stack& s, bool specialised, bool series = true, bool orders = false,
                     uint32_t max_events = 256, bool branching = true);

}   // namespace gonio
