// progress.h: a one-line progress report with ETA on stderr, shown only for runs longer than a second.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace gonio {

class Progress {
public:
    Progress(bool enabled, std::string label, uint64_t total);
    // where: the incident angles being traced (angles_label); rse >= 0: also show the current relative standard
    // error (of the angle furthest from its target) against the target
    void update(uint64_t done, const std::string& where, double rse = -1.0, double rse_target = 0.0);
    void finish();

private:
    bool enabled_;
    bool tty_;   // a terminal gets one line rewritten in place; a log gets a line every 10 s
    bool shown_ = false;
    uint64_t done_ = 0;
    std::string label_;
    uint64_t total_;
    std::chrono::steady_clock::time_point start_, last_;
};

// The angles being traced, for Progress::update: "theta_i 30 (2/4)" for one (index first_index of count),
// "theta_i 0 to 88, 45 at once (3/45 done)" for several side by side (theta_lo to theta_hi, `finished` done).
std::string angles_label(double theta_lo, double theta_hi, size_t active, size_t first_index, size_t finished,
                         size_t count);

}   // namespace gonio
