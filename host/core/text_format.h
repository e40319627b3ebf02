// text_format.h: numbers as text in gonio's output files (slices.csv, sweep.csv; summary.json rounds through it,
// json.h): printf's "%.9g", 9 significant digits, so a float round-trips. Written with std::to_chars, which in the C
// locale gives printf's bytes (checked on 4e6 random doubles and the special values) about 6x faster: a compare run's
// slices.csv holds millions of numbers, and snprintf's exact decimal conversion would take a third of its CPU time.
#pragma once
#include <charconv>
#include <string>

namespace gonio {

inline std::string format_g9(double v) {
    char b[40];
    auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, 9);
    return std::string(b, r.ptr);
}

// The shortest text that reads back to exactly the same float (stack files, and the ranges in their refusals).
inline std::string format_shortest(float v) {
    char b[32];
    auto r = std::to_chars(b, b + sizeof b, v);
    return std::string(b, r.ptr);
}

}   // namespace gonio
