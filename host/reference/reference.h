// reference.h: the reference virtual gonio-photometer: trace paths through a stack and histogram them.
#pragma once
#include "stack.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct SimResult;

struct SimOptions {
    std::vector<double> theta_i_deg{0.0};
    uint64_t paths = 1000000;          // per incident angle
    uint32_t seed = 1;
    double dtheta_deg = 1.0;           // bin width in theta (must divide 90)
    double dphi_deg = 2.0;             // bin width in phi (must divide 180)
    bool orders = false;               // split the histogram by path class (0, 1, 2+ internal reversals)
    uint32_t max_events = 256;         // event cap per path (energy beyond it is counted as truncated)
    bool specialised = true;           // false: the general N-layer walk (for benchmarks)
    bool series = true;                // the Lambertian series where it applies (walk.glsl); false: every trip traced
    bool baked_stack = true;           // a specialised walk of at most two layers gets the stack's parameters compiled
                                       // into its shader (stack_constants.glsl); false: read from a uniform buffer, as
                                       // sweeps' batches and the viewer do (the same paths; rounding can differ)
    bool progress = false;             // progress line with ETA on stderr for runs longer than a second
    uint64_t batch_paths = 0;          // paths per dispatch; 0: adaptive (results do not depend on it)
    uint32_t paths_per_invocation = 16;
    // Run until the rse_quantile quantile of the relative standard errors of the bins above 1% of their slice's
    // peak (per side and channel) is below rse_target (0: off): 0.5, the median; 1, the worst bin. Paths then grow
    // in rounds, 2^20 x 2^k per angle, so the stopping point is reproducible; `paths` is the cap.
    double rse_target = 0.0;
    double rse_quantile = 0.5;
    double max_seconds = 0.0;          // per incident angle; 0: no limit. Stopping on time is reported.
    uint32_t invalid_path_for_tests = 0xffffffffu;   // the tests of the invalid class: this path's weight is made NaN
    // Called with the run so far (finished angles, the current one's sums, the angles still to come with no paths)
    // at least every checkpoint_seconds of tracing: resuming from it gives the bytes of one uninterrupted run.
    double checkpoint_seconds = 0.0;
    std::function<void(const SimResult&)> on_checkpoint;
};

// Throws std::invalid_argument with a clear message for options that cannot work.
void validate_options(const SimOptions& o);

struct AngleResult {
    double theta_i_deg = 0.0;
    uint64_t paths = 0;
    std::vector<uint64_t> raw;         // [class][side < n_sides][theta][phi][6]: sum w (RGB), sum w^2 (RGB), units of 2^-12
    int64_t energy[12] = {};           // absorbed RGB, lost RGB, truncated RGB, invalid RGB, fixed point (kEnergyScale)
    double seconds = 0.0;              // wall clock of this angle (includes the first-dispatch JIT)
    double device_seconds = 0.0;       // sum of device timestamp intervals of the dispatches
    std::string stopped_by = "paths";  // "paths" (reached --paths), "rse" (target met), "max_seconds"
    double worst_rse = 0.0;            // largest relative standard error over bins above 1% of their peak
    double median_rse = 0.0, p90_rse = 0.0;   // the median and 90th percentile over the same bins
};

struct SimResult {
    Stack stack;
    SimOptions options;
    std::string device;
    std::string driver;
    uint32_t n_theta = 0, n_phi = 0, n_classes = 1;
    uint32_t n_sides = 2;              // histogram sides: 2 (reflection, transmission), 1 for an opaque stack (no
                                       // transmission bins: nothing can leave through its bottom)
    std::vector<AngleResult> angles;
};

inline constexpr double kFixedScale = 4096.0;          // 2^12, as FIXED_SCALE in shaders/lib/bins.glsl
inline constexpr double kEnergyScale = 16777216.0;    // 2^24, as ENERGY_SCALE
inline constexpr size_t kEnergyEntries = 12;          // ENERGY_ENTRIES in bins.glsl (checked in reference_cpu.cpp)
// The most paths one incident angle may trace: the energy book adds up to 2^24 per path in a signed 64-bit integer.
inline constexpr uint64_t kMaxPathsPerAngle = 1ull << 38;
// Throws std::invalid_argument, saying how large the grid is and what the device allows, if the histograms of a run
// (bins x sides x path classes) do not fit the device's buffers or memory.
void check_histograms_fit(VkContext& ctx, uint64_t histogram_bytes, const std::string& what);

// resume: an earlier result of the same stack and options (seed, bins, angles, events, orders) with fewer
// paths; the run continues it exactly as one longer run would have (paths are numbered, sums are integers).
SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt, const SimResult* resume = nullptr);

// Many stacks of the same shape at once (gonio sweep): each workgroup row of one dispatch traces one stack with
// its own seed into its own histograms (shaders/simulate_batch.comp). rse_target works as in simulate_gpu, per
// stack and angle (a stack that meets it stops taking paths); no max_seconds or resume. specialised: the walk specialised for the stacks' common shape (then every stack must
// have the same specialisation: layer count, base kind, rough and absorbing layers), else the general walk.
// Result i equals simulate_gpu's for stacks[i] with seed seeds[i] and the same `specialised` (and rse_target),
// bit for bit, paths included.
std::vector<SimResult> simulate_gpu_batch(VkContext& ctx, const std::vector<Stack>& stacks, const std::vector<uint32_t>& seeds,
                                          const SimOptions& opt);

// The relative standard errors of the bins of one angle whose value is above 1% of their slice's peak (per side
// and channel): the quantile q of them (q = 1: the largest; the nearest-rank quantile); 0 if nothing left the stack.
double relative_se_quantile(const SimResult& r, const AngleResult& a, double q);
inline double worst_relative_se(const SimResult& r, const AngleResult& a) { return relative_se_quantile(r, a, 1.0); }
// Sets a's worst_rse, median_rse and p90_rse.
void summarise_relative_se(const SimResult& r, AngleResult& a);

// The same walk on the CPU (the twin), with `threads` threads. Same output format and statistics; not
// bit-identical to the device (transcendental functions differ in the last bits).
SimResult simulate_cpu(const Stack& stack, const SimOptions& opt, unsigned threads);

}  // namespace gonio
