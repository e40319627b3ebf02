// reference.h: the reference virtual gonio-photometer: trace paths through a stack and histogram them.
#pragma once
#include "bins.glsl"   // FIXED_SCALE, ENERGY_SCALE, ENERGY_ENTRIES
#include "sim_options.h"
#include "stack.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct AngleResult {
    double theta_i_deg = 0.0;
    double phi_i_deg = 0.0;   // the incident azimuth (SimOptions::phi_i_deg)
    uint64_t paths = 0;
    std::vector<uint64_t> raw;   // [class][side < n_sides][theta][phi][6]: sum w (RGB), sum w^2 (RGB), units of 2^-12
    int64_t energy[ENERGY_ENTRIES] =
        {};   // absorbed RGB, lost RGB, truncated RGB, invalid RGB, fixed point (kEnergyScale)
    double seconds = 0.0;   // wall clock of this angle (includes the first-dispatch JIT)
    double device_seconds = 0.0;   // sum of device timestamp intervals of the dispatches
    std::string stopped_by = "paths";   // "paths" (reached --paths), "rse" (target met), "max_seconds"
    double worst_rse = 0.0;   // largest relative standard error over bins above 1% of their peak
    double median_rse = 0.0, p90_rse = 0.0;   // the median and 90th percentile over the same bins
};

// The walk a run ran (summary.json's "walk"), recorded by the host that ran it.
struct WalkRan {
    bool specialised = true;   // the walk specialised for the stack (false: the general walk, --general-walk)
    bool baked_stack = false;   // the stack's parameters compiled into the shader (stack_constants.glsl)
    bool series = false;   // the Lambertian series (docs/PHYSICS.md)
    bool entry_branch = false;   // the entry's both branches (docs/PHYSICS.md, "Booking estimators")
    uint32_t exit_estimates = 0;   // fresh exit estimates per path (docs/PHYSICS.md, "Booking estimators")
};

struct SimResult {
    Stack stack;
    SimOptions options;
    std::string device;
    std::string driver;
    uint32_t n_theta = 0, n_phi = 0, n_classes = 1;
    uint32_t n_sides = 2;   // histogram sides: 2 (reflection, transmission), 1 for an opaque stack (no
        // transmission bins: nothing can leave through its bottom)
    std::vector<AngleResult> angles;
    WalkRan walk;
};

inline const double kFixedScale = FIXED_SCALE;   // the histogram's fixed point, 2^12 (bins.glsl)
inline const double kEnergyScale = ENERGY_SCALE;   // the energy book's, 2^24
inline constexpr size_t kEnergyEntries = ENERGY_ENTRIES;
// The most paths one incident angle may trace: the energy book adds up to 2^24 per path in a signed 64-bit integer.
inline constexpr uint64_t kMaxPathsPerAngle = 1ull << 38;

// Throws std::invalid_argument naming what differs if `previous` cannot be continued by a run of
// (stack, opt).
void check_resumable(const SimResult& previous, const Stack& stack, const SimOptions& opt);

// Throws std::invalid_argument where a run of these options is at an incident azimuth other than 0 (simulate
// --phi-i): `what` (the models' bins, a render's table) takes the plane of incidence, phi_i = 0, only.
void require_plane_of_incidence(const SimOptions& opt, const std::string& what);

// resume: an earlier result of the same stack and options (seed, bins, angles, events, orders) with fewer
// paths; the run continues it exactly as one longer run would have (paths are numbered, sums are integers).
SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt, const SimResult* resume = nullptr);

// Many stacks of the same shape at once (gonio sweep): each workgroup row of one dispatch traces one stack with
// its own seed into its own histograms (shaders/simulate_batch.comp). rse_target works as in simulate_gpu, per
// stack and angle (a stack that meets it stops taking paths); no max_seconds or resume. specialised: the walk specialised for the stacks' common shape (then every stack must
// have the same specialisation: layer count, base kind, rough and absorbing layers), else the general walk.
// Result i equals simulate_gpu's for stacks[i] with seed seeds[i] and the same `specialised` (and rse_target),
// bit for bit, paths included. paths: stack i's paths per angle (its cap under rse_target), empty for opt.paths in
// every stack; its result is then simulate_gpu's with opt.paths = paths[i].
std::vector<SimResult> simulate_gpu_batch(VkContext& ctx, const std::vector<Stack>& stacks,
                                          const std::vector<uint32_t>& seeds, const SimOptions& opt,
                                          const std::vector<uint64_t>& paths = {});
// The stacks that can share one batch's kernel under `opt` (the same layers and base kind; with opt.specialised the
// same specialisation), as groups of indices into `stacks` in their order, each group as many stacks as the device's
// memory holds the histograms of (at least one).
std::vector<std::vector<size_t>> batch_groups(VkContext& ctx, const std::vector<Stack>& stacks, const SimOptions& opt);

// The same walk on the CPU (the twin), with `threads` threads. Same output format and statistics; not
// bit-identical to the device (transcendental functions differ in the last bits).
SimResult simulate_cpu(const Stack& stack, const SimOptions& opt, unsigned threads);

// The mean number of scattering events (interface events and medium collisions) of a path at the first incident
// angle, over `paths` paths of the CPU twin's walk (one thread): what a path costs, for `gonio bench`.
double mean_events_per_path(const Stack& stack, const SimOptions& opt, uint64_t paths);

}   // namespace gonio
