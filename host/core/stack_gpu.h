// stack_gpu.h: a parsed Stack turned into what the walk reads (uniform block and specialisation).
#pragma once
#include "cpu_twin.h"
#include "stack.h"

namespace gonio {

// The stack's layers (what the models read too); series: off (gain 0, weight scale 1).
StackGpu pack_stack(const Stack& s);
// specialised = false gives the general N-layer walk (everything read from the uniform block). The Lambertian
// series (lambertian_series.h) is on where it applies, the walk is specialised, `series` allows it, the histogram
// is not split by path class (`orders`: the series sums the classes) and max_events leaves room for its 3 events.
WalkSpec walk_spec(const Stack& s, bool specialised, bool series = true, bool orders = false, uint32_t max_events = 256);
// What the walk reads: pack_stack and, where ws.series, the series' terms. weight_shift: the staging histogram's
// scale 2^-shift (fold.comp); -1 picks the stack's own (lambertian_series), a batch passes its stacks' largest.
StackGpu pack_walk_stack(const Stack& s, const WalkSpec& ws, int weight_shift = -1);
// Whether simulate_gpu bakes the stack's parameters into its pipeline (specialisation constants,
// shaders/lib/stack_constants.glsl): a specialised walk of at most two layers, whose layer indices are then all
// compile-time constants. The general walk and longer stacks read the uniform block.
bool walk_has_constant_stack(const WalkSpec& ws);
// The staging scale a walk of s with ws needs: weights up to 2^shift (0 unless the series is on).
int walk_weight_shift(const Stack& s, const WalkSpec& ws);

}  // namespace gonio
