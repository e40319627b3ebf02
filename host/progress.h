// progress.h: a one-line progress report with ETA on stderr, shown only for runs longer than a second.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace gonio {

class Progress {
public:
    Progress(bool enabled, std::string label, uint64_t total);
    void update(uint64_t done, size_t angle_index, size_t angle_count, double theta_i_deg);
    void finish();

private:
    bool enabled_;
    bool shown_ = false;
    std::string label_;
    uint64_t total_;
    std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace gonio
