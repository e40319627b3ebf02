// node_files.h: the files of a model in any language: what `gonio nodes` writes (nodes.json's format number, the
// nodes as .npy) and `gonio score` reads back (the grid of bins the nodes lie in, the values of f at the nodes).
#pragma once
#include "model_evaluator.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

constexpr int kNodesFormat = 1;   // nodes.json's "gonio_nodes"

inline ModelGrid grid_of(const std::vector<double>& theta_i, double dtheta, double dphi) {
    return {uint32_t(std::lround(90.0 / dtheta)), uint32_t(std::lround(360.0 / dphi)), dtheta, dphi, theta_i};
}

// NumPy's .npy format 1.0 (numpy.lib.format) of rows x cols float64 in C order.
void write_npy_f8(const std::string& path, const std::vector<double>& data, size_t rows, size_t cols);
// The values file: one row per node, in nodes.csv's order, "r,g,b" (an optional header line r,g,b first); a value
// that is negative, NaN or infinite is refused (StackError: the file and line), nothing is clamped.
std::vector<glm::dvec3> read_values(const std::string& path);
// Values as .npy: shape (nodes, 3), float64 or float32, C order, little-endian (numpy.save of an array r,g,b).
std::vector<glm::dvec3> read_values_npy(const std::string& path);

}   // namespace gonio
