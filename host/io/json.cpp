#include "json.h"
#include "input_file.h"
#include "text_format.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gonio {

namespace {

// The number a printf-style text says: an integer if it is one ("-12"), else the double it parses to.
Json number_of_text(const std::string& t) {
    bool integer = !t.empty();
    for (size_t i = 0; i < t.size(); ++i)
        integer &= (t[i] >= '0' && t[i] <= '9') || (i == 0 && t[i] == '-' && t.size() > 1);
    if (integer && t.size() <= 18) return Json(std::strtoll(t.c_str(), nullptr, 10));
    return Json(std::strtod(t.c_str(), nullptr));
}

std::string to_text(double v, std::chars_format fmt, int precision) {
    char b[400];
    auto r = std::to_chars(b, b + sizeof b, v, fmt, precision);
    return std::string(b, r.ptr);
}

}   // namespace

std::atomic<uint64_t>& non_finite_json_numbers() {
    static std::atomic<uint64_t> n{0};
    return n;
}

Json json_number(double v) {
    if (!std::isfinite(v)) {
        ++non_finite_json_numbers();
        return Json(nullptr);
    }
    return number_of_text(format_g9(v));
}

Json json_rgb(const glm::dvec3& v) { return Json::array({json_number(v.x), json_number(v.y), json_number(v.z)}); }

Json json_rounded(double v, int digits) {
    return std::isfinite(v) ? number_of_text(to_text(v, std::chars_format::general, digits)) : Json(nullptr);
}

Json json_fixed(double v, int decimals) {
    return std::isfinite(v) ? number_of_text(to_text(v, std::chars_format::fixed, decimals)) : Json(nullptr);
}

// The library writes a double with digits that read back to it, but not always the fewest (0.382164798 can come out
// as 0.38216479799999997): every number outside a string is written again as the shortest text of the same double.
std::string shortest_numbers(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    bool in_string = false;
    for (size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (in_string) {
            out += c;
            if (c == '\\' && i + 1 < text.size())
                out += text[++i];
            else if (c == '"')
                in_string = false;
            ++i;
            continue;
        }
        if (c == '"') {
            in_string = true;
            out += c;
            ++i;
            continue;
        }
        if (c == '-' || (c >= '0' && c <= '9')) {
            size_t j = i;
            bool fractional = false;
            while (j < text.size() && std::strchr("0123456789+-.eE", text[j]))
                fractional |= std::strchr(".eE", text[j++]) != nullptr;
            const std::string token = text.substr(i, j - i);
            if (fractional) {
                const double v = std::strtod(token.c_str(), nullptr);
                char b[64];
                auto r = std::to_chars(b, b + sizeof b, v);
                std::string t(b, r.ptr);
                // keep a JSON float a float: 3 would read back as an integer
                if (t.find_first_of(".e") == std::string::npos) t += ".0";
                out += t;
            } else {
                out += token;
            }
            i = j;
            continue;
        }
        out += c;
        ++i;
    }
    return out;
}

std::string json_text(const Json& j) {
    return shortest_numbers(j.dump(2, ' ', false, Json::error_handler_t::replace)) + "\n";
}

void write_json_file(const std::string& path, const Json& j) {
    const std::string text = json_text(j);
    std::ofstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot write " + path);
    f << text;
    if (!f) throw std::runtime_error("error writing " + path);
}

Json read_json_file(const std::string& path) {
    const std::string why = input_file_refusal(path, "JSON file", kMaxValuesFileBytes);
    if (!why.empty()) throw std::invalid_argument(path + ": " + why);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::invalid_argument("cannot read " + path);
    std::stringstream ss;
    ss << f.rdbuf();
    try {
        return Json::parse(ss.str());
    } catch (const Json::exception& e) { throw std::invalid_argument(path + ": not valid JSON (" + e.what() + ")"); }
}

}   // namespace gonio
