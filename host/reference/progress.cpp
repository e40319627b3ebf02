#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace gonio {

Progress::Progress(bool enabled, std::string label, uint64_t total)
    : enabled_(enabled),
      tty_(isatty(fileno(stderr)) != 0),
      label_(std::move(label)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

std::string angles_label(double theta_lo, double theta_hi, size_t active, size_t first_index, size_t finished,
                         size_t count) {
    char buf[128];
    if (active == 1)
        std::snprintf(buf, sizeof buf, "theta_i %g (%zu/%zu)", theta_lo, first_index + 1, count);
    else
        std::snprintf(buf, sizeof buf, "theta_i %g to %g, %zu at once (%zu/%zu done)", theta_lo, theta_hi, active,
                      finished, count);
    return buf;
}

void Progress::update(uint64_t done, const std::string& where, double rse, double rse_target) {
    done_ = done;
    if (!enabled_) return;
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || std::chrono::duration<double>(now - last_).count() < (tty_ ? 0.2 : 10.0)) return;
    last_ = now;
    shown_ = true;
    const char* lead = tty_ ? "\r" : "";
    const char* tail = tty_ ? "   " : "\n";
    double rate = double(done) / elapsed;
    double eta = rate > 0 ? double(total_ - done) / rate : 0.0;
    if (rse >= 0) {
        // paths still needed if the error falls as 1/sqrt(N): N (rse/target)^2; the ETA is for this angle
        double need = rse > 0 ? double(done) * (rse / rse_target) * (rse / rse_target) : double(done);
        double eta_rse = rate > 0 ? std::max(0.0, need - double(done)) / rate : 0.0;
        std::fprintf(
            stderr, "%s%s: %s  %.3g Mpaths  rse %.4f (target %.4f)  %.3g Mpaths/s  elapsed %.0f s  ETA %.0f s%s", lead,
            label_.c_str(), where.c_str(), double(done) * 1e-6, rse, rse_target, rate * 1e-6, elapsed, eta_rse, tail);
    } else {
        std::fprintf(stderr, "%s%s: %s  %5.1f%%  %.3g Mpaths/s  elapsed %.0f s  ETA %.0f s%s", lead, label_.c_str(),
                     where.c_str(), 100.0 * double(done) / double(total_), rate * 1e-6, elapsed, eta, tail);
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (!enabled_ || !shown_) return;
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "%s%s: done, %llu paths in %.1f s (%.3g Mpaths/s)%s\n", tty_ ? "\r" : "", label_.c_str(),
                 (unsigned long long)done_, elapsed, double(done_) / elapsed * 1e-6,
                 tty_ ? "                              " : "");
}

}   // namespace gonio
