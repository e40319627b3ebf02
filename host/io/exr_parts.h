// exr_parts.h: a multi-part EXR of float planes, the form of gonio's bin files (output.cpp's runs and models,
// spectral_output.cpp's spectral runs): one scanline part per slice, each with its name, its attributes and its
// named width x height planes.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace gonio {

struct ExrPart {
    std::string name;
    std::vector<std::pair<std::string, std::variant<std::string, double, int>>> attributes;
    std::vector<std::pair<std::string, std::vector<float>>> planes;   // channel name, values row by row

    void attribute(const std::string& key, std::variant<std::string, double, int> value) {
        attributes.emplace_back(key, std::move(value));
    }
    // a channel of n values, value(i) for i in [0, n)
    template <class Value>
    void plane(const std::string& channel, size_t n, Value value) {
        std::vector<float> p(n);
        for (size_t i = 0; i < n; ++i) p[i] = float(value(i));
        planes.emplace_back(channel, std::move(p));
    }
};

// The parts, each width x height with FLOAT channels, into one file (OpenEXR's exceptions pass through).
void write_exr_parts(const std::string& path, int width, int height, const std::vector<ExrPart>& parts);

}   // namespace gonio
