// sim_options.h: the options of a reference run (simulate_gpu, its batch and the CPU twin) and their checks.
#pragma once
#include "stack.h"
#include "stack_gpu.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace gonio {

struct SimResult;

struct SimOptions {
    std::vector<double> theta_i_deg{0.0};
    // The incident azimuth of every angle of the run, degrees in [0, 360) (bins.glsl incident_direction): 0, the plane
    // of incidence xz that the phi bins are centred on and the models' bins take
    double phi_i_deg = 0.0;
    uint64_t paths = 1000000;   // per incident angle
    uint32_t seed = 1;
    double dtheta_deg = 1.0;   // bin width in theta (must divide 90)
    double dphi_deg = 2.0;   // bin width in phi (must divide 180)
    bool orders = false;   // split the histogram by path class (0, 1, 2+ internal reversals)
    uint32_t max_events = 256;   // event cap per path (energy beyond it is counted as truncated)
    bool specialised = true;   // false: the general N-layer walk (for benchmarks)
    bool series = true;   // the Lambertian series where it applies (walk.glsl); false: every trip traced
    bool branching = true;   // the booking estimators where they apply (trace_book.glsl); false: the analog walk
    bool baked_stack = true;   // a specialised walk of at most two layers gets the stack's parameters compiled
        // into its shader (stack_constants.glsl); false: read from a uniform buffer, as
        // sweeps' batches and the viewer do (the same paths; rounding can differ)
    bool progress = false;   // progress line with ETA on stderr for runs longer than a second
    uint64_t batch_paths = 0;   // paths per dispatch and angle; 0: adaptive (results do not depend on it)
    // Incident angles traced side by side in one dispatch sequence (simulate_gpu): 0, as many as the device's memory
    // holds (every angle of a table, usually); 1, one angle after the other. Results do not depend on it.
    uint32_t angles_per_dispatch = 0;
    uint32_t paths_per_invocation = 16;
    // Run until the rse_quantile quantile of the relative standard errors of the bins above 1% of their slice's
    // peak (per side and channel) is below rse_target (0: off): 0.5, the median; 1, the worst bin. Paths then grow
    // in rounds, 2^20 x 2^k per angle, so the stopping point is reproducible; `paths` is the cap.
    double rse_target = 0.0;
    double rse_quantile = 0.5;
    double max_seconds = 0.0;   // per incident angle (its share by paths of the dispatches it took part in); 0: no
        // limit. Stopping on time is reported.
    uint32_t invalid_path_for_tests = 0xffffffffu;   // the tests of the invalid class: this path's weight is made NaN
    uint32_t fault_for_tests = 0;   // the tests' negative controls: a FAULT_* of kernel_interface.glsl (GPU walk only)
    // Called with the run so far (finished angles, the current one's sums, the angles still to come with no paths)
    // at least every checkpoint_seconds of tracing: resuming from it gives the bytes of one uninterrupted run.
    double checkpoint_seconds = 0.0;
    std::function<void(const SimResult&)> on_checkpoint;
    // Called after every dispatch of the device walk (simulate_gpu, simulate_gpu_batch) with the paths traced so far
    // and the run's total (paths x angles, and stacks in a batch: with --rse, the cap): the Python module's progress
    // callback and Ctrl-C, which stop the run by throwing from it (no sums are then returned).
    std::function<void(uint64_t done, uint64_t total)> on_progress;
};

// Whether a bin width w (degrees) divides `range` into a whole number (1 or more) of bins.
bool bin_width_divides(double w, double range);
// Throws std::invalid_argument with a clear message for options that cannot work.
void validate_options(const SimOptions& o);
// What validate_options bounds: the incident angles of one run (a state file holds no more), and the histograms the
// host keeps for them
constexpr size_t kMaxIncidentAngles = 1000;
constexpr uint64_t kMaxHistogramBytes = uint64_t(16) << 30;

// What the stack implies for the walk these options ask for (its specialisation, packing and series).
WalkStack walk_stack_for(const Stack& stack, const SimOptions& o);

}   // namespace gonio
