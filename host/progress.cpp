#include "progress.h"

#include <cstdio>

namespace gonio {

Progress::Progress(bool enabled, std::string label, uint64_t total)
    : enabled_(enabled), label_(std::move(label)), total_(total),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(uint64_t done, size_t angle_index, size_t angle_count, double theta_i_deg) {
    if (!enabled_) return;
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || std::chrono::duration<double>(now - last_).count() < 0.2) return;
    last_ = now;
    shown_ = true;
    double rate = double(done) / elapsed;
    double eta = rate > 0 ? double(total_ - done) / rate : 0.0;
    std::fprintf(stderr, "\r%s: theta_i %g (%zu/%zu)  %5.1f%%  %.3g Mpaths/s  elapsed %.0f s  ETA %.0f s   ",
                 label_.c_str(), theta_i_deg, angle_index + 1, angle_count, 100.0 * double(done) / double(total_),
                 rate * 1e-6, elapsed, eta);
    std::fflush(stderr);
}

void Progress::finish() {
    if (!enabled_ || !shown_) return;
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\r%s: done, %llu paths in %.1f s (%.3g Mpaths/s)%30s\n", label_.c_str(),
                 (unsigned long long)total_, elapsed, double(total_) / elapsed * 1e-6, "");
}

}  // namespace gonio
