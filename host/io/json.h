// json.h: gonio's JSON files (summary.json, sweep.json, sweep-bench.json, bench.json), built and read with
// nlohmann::json (Debian's nlohmann-json3-dev). Members keep the order they are added in (ordered_json).
#pragma once
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <atomic>
#include <cstdint>
#include <string>

namespace gonio {

using Json = nlohmann::ordered_json;

// A number in a JSON file, rounded to 9 significant digits (printf's "%.9g", format_g9: a float round-trips). The
// value is the double that the rounded text parses to, and a whole number is an integer ("60", not "60.0"), so that
// readers get the values and JSON types of the rounded text. JSON has no NaN or Inf: a value that is not finite is
// written as null and counted (non_finite_json_numbers), and the command that wrote it says so and exits 1.
Json json_number(double v);
std::atomic<uint64_t>& non_finite_json_numbers();
// The same for an RGB triple: [r, g, b].
Json json_rgb(const glm::dvec3& v);

// Rounded as printf's "%.<digits>g" ("%.<decimals>f"), for numbers that are not results (timings, bench figures); a
// value that is not finite is null and not counted.
Json json_rounded(double v, int digits);
Json json_fixed(double v, int decimals);

// The file's text: indented by two spaces, one member per line, a final newline. Bytes that are not UTF-8 (a file
// name) are written as U+FFFD.
std::string json_text(const Json& j);
// Writes json_text(j) to `path`; throws std::runtime_error if it cannot.
void write_json_file(const std::string& path, const Json& j);
// Parses the JSON file at `path`; throws std::invalid_argument naming it if it cannot be read or is not JSON.
Json read_json_file(const std::string& path);

}   // namespace gonio
