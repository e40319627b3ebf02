// bin_check.h: the acceptance rule of the closed-form tests, bin by bin against exact bin averages (1/sr).
//
// Per bin and channel: |simulated - exact| <= 3 se + 0.5% of exact (two Monte Carlo runs: 3 se alone). With thousands of bins some exceed 3 se by
// chance (0.27% each), so a check requires (a) no bin beyond 5.5 se + 0.5% and (b) at most as many 3-se exceedances
// as a binomial(n, 0.0027) gives with probability 1 - 1e-4. Bins expecting fewer than 100 paths (se itself
// unreliable there) are pooled into one comparison.
#pragma once
#include "gpu_fixture.h"

#include <cstdio>
#include <functional>
#include <string>
#include <thread>

namespace gonio_test {

using namespace gonio;

struct BinCheck {
    int compared = 0, over3 = 0, over_max = 0;
    double worst_z = 0;
    std::string worst;
};

// The most 3-se exceedances n comparisons have by chance, with probability 1 - 1e-4.
inline double allowed_over3(const BinCheck& c) {
    const double n = c.compared, p = 0.0027;
    return n * p + 4.0 * std::sqrt(n * p * (1 - p)) + 1.0;
}

// The rule's verdict: something compared, no bin beyond 5.5 se, no more 3-se exceedances than chance gives.
inline bool within_noise(const BinCheck& c) { return c.compared > 0 && c.over_max == 0 && c.over3 <= allowed_over3(c); }

inline void expect_matches(const BinCheck& c, const std::string& what) {
    std::printf("%s: %d bin-channels compared, %d beyond 3 se (+ slack) (allowed %.1f), worst z %.2f at %s\n",
                what.c_str(), c.compared, c.over3, allowed_over3(c), c.worst_z, c.worst.c_str());
    EXPECT_GT(c.compared, 0) << what;
    EXPECT_EQ(c.over_max, 0) << what << ": a bin is beyond 5.5 se (+ slack) (worst " << c.worst << ")";
    EXPECT_LE(c.over3, allowed_over3(c)) << what << ": too many bins beyond 3 se (+ slack)";
}

// One comparison: |sim - ex| against 3 and 5.5 se plus relative_slack x ex (0.5% against a closed form, for its
// quadrature and float rounding; 0 between two Monte Carlo runs, which differ by their noise alone).
inline void check_value(BinCheck& c, double sim, double se, double ex, const std::string& where,
                        double relative_slack = 0.005) {
    double d = std::fabs(sim - ex), slack = relative_slack * std::fabs(ex);
    double z = se > 0 ? (d - slack) / se : (d > slack ? 1e9 : 0.0);
    c.compared++;
    if (d > 3 * se + slack) c.over3++;
    if (d > 5.5 * se + slack) c.over_max++;
    if (z > c.worst_z) {
        c.worst_z = z;
        c.worst = where + " sim " + std::to_string(sim) + " exact " + std::to_string(ex) + " se " + std::to_string(se);
    }
}

// Compares every bin of a slice against exact bin averages exact(t, p, c) (1/sr); bins expecting fewer than
// 100 paths are pooled into one comparison of their summed fractions.
inline void compare_bins(BinCheck& check, const Slice& sl, const BinGrid& g, uint64_t paths, int channels,
                         const std::function<double(uint32_t, uint32_t, int)>& exact, const std::string& label,
                         double weight_scale = 1.0) {
    for (int c = 0; c < channels; ++c) {
        double pooled_sim = 0, pooled_var = 0, pooled_ex = 0;
        for (uint32_t t = 0; t < g.n_theta; ++t) {
            const double omega = g.projected_solid_angle(t);
            for (uint32_t p = 0; p < g.n_phi; ++p) {
                const double f = exact(t, p, c);
                const size_t b = size_t(t) * g.n_phi + p;
                // paths expected in the bin (weights are at most weight_scale)
                if (f * omega * double(paths) / weight_scale < 100) {
                    pooled_sim += sl.f[b][c] * omega;
                    pooled_ex += f * omega;
                    pooled_var += std::pow(sl.se[b][c] * omega, 2);
                    continue;
                }
                char where[128];
                std::snprintf(where, sizeof where, "%s bin (%u,%u) ch %d", label.c_str(), t, p, c);
                check_value(check, sl.f[b][c], sl.se[b][c], f, where);
            }
        }
        if (pooled_ex > 0)
            check_value(check, pooled_sim, std::sqrt(pooled_var), pooled_ex, label + " pooled low-count bins");
    }
}

inline SimResult run(const Stack& s, SimOptions o, bool cpu) {
    return cpu ? simulate_cpu(s, o, std::max(1u, std::thread::hardware_concurrency())) : simulate_gpu(context(), s, o);
}

}   // namespace gonio_test
