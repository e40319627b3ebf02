// progress.h: a one-line progress report with ETA on stderr, shown only for runs longer than a second.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace gonio {

class Progress {
public:
    Progress(bool enabled, std::string label, uint64_t total);
    // rse >= 0: also show the current worst relative standard error against its target
    void update(uint64_t done, size_t angle_index, size_t angle_count, double theta_i_deg, double rse = -1.0,
                double rse_target = 0.0);
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

}   // namespace gonio
