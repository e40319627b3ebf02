// reference.h: the reference virtual gonio-photometer: trace paths through a stack and histogram them.
#pragma once
#include "stack.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct SimOptions {
    std::vector<double> theta_i_deg{0.0};
    uint64_t paths = 1000000;          // per incident angle
    uint32_t seed = 1;
    double dtheta_deg = 1.0;           // bin width in theta (must divide 90)
    double dphi_deg = 2.0;             // bin width in phi (must divide 180)
    bool orders = false;               // split the histogram by path class (0, 1, 2+ internal reversals)
    uint32_t max_events = 256;         // event cap per path (energy beyond it is counted as truncated)
    bool specialised = true;           // false: the general N-layer walk (for benchmarks)
    bool progress = false;             // progress line with ETA on stderr for runs longer than a second
    uint64_t batch_paths = 0;          // paths per dispatch; 0: adaptive (results do not depend on it)
    uint32_t paths_per_invocation = 16;
};

// Throws std::invalid_argument with a clear message for options that cannot work.
void validate_options(const SimOptions& o);

struct AngleResult {
    double theta_i_deg = 0.0;
    uint64_t paths = 0;
    std::vector<uint64_t> raw;         // [class][side][theta][phi][6]: sum w (RGB), sum w^2 (RGB), units of 2^-12
    int64_t energy[9] = {};            // absorbed RGB, lost RGB, truncated RGB, fixed point (kEnergyScale)
    double seconds = 0.0;              // wall clock of this angle (includes the first-dispatch JIT)
    double device_seconds = 0.0;       // sum of device timestamp intervals of the dispatches
};

struct SimResult {
    Stack stack;
    SimOptions options;
    std::string device;
    std::string driver;
    uint32_t n_theta = 0, n_phi = 0, n_classes = 1;
    std::vector<AngleResult> angles;
};

inline constexpr double kFixedScale = 4096.0;          // 2^12, as FIXED_SCALE in shaders/lib/bins.glsl
inline constexpr double kEnergyScale = 16777216.0;    // 2^24, as ENERGY_SCALE

SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt);
// The same walk on the CPU (the twin), with `threads` threads. Same output format and statistics; not
// bit-identical to the device (transcendental functions differ in the last bits).
SimResult simulate_cpu(const Stack& stack, const SimOptions& opt, unsigned threads);

}  // namespace gonio
