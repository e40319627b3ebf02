// text_format.h: numbers as text in gonio's output files (slices.csv, summary.json, sweep.csv): printf's "%.9g",
// 9 significant digits, so a float round-trips. Written with std::to_chars, which in the C locale gives printf's
// bytes (checked on 4e6 random doubles and the special values) about 6x faster: a compare run's slices.csv holds
// millions of numbers, and snprintf's exact decimal conversion was a third of its CPU time.
#pragma once
#include <atomic>
#include <charconv>
#include <cmath>
#include <string>

namespace gonio {

inline std::string format_g9(double v) {
    char b[40];
    auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, 9);
    return std::string(b, r.ptr);
}

// A number in a JSON file. JSON has no NaN or Inf: a value that is not finite is written as null and counted
// (non_finite_json_numbers), and the command that wrote it says so and exits 1.
inline std::atomic<uint64_t>& non_finite_json_numbers() {
    static std::atomic<uint64_t> n{0};
    return n;
}
inline std::string json_number(double v) {
    if (!std::isfinite(v)) {
        ++non_finite_json_numbers();
        return "null";
    }
    return format_g9(v);
}

}  // namespace gonio
