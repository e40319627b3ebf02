// node_files.h: the files of a model in any language: what `gonio nodes` writes (nodes.json's format number, the
// nodes as .npy) and `gonio score` reads back (the grid of bins the nodes lie in, the values of f at the nodes).
#pragma once
#include "bin_nodes.h"
#include "input_file.h"
#include "model_evaluator.h"
#include "stack.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

constexpr int kNodesFormat = 1;   // nodes.json's "gonio_nodes"
constexpr int kMaxNodesPerBinSide = 16;   // --nodes-per-bin K: K x K nodes per bin

// The most nodes gonio nodes writes: what a values file gonio score reads can hold (.npy, 3 float64 a node, 1 GiB)
constexpr uint64_t kMaxNodes = kMaxValuesFileBytes / 24;
// angles x sides x bins x k^2, or why a grid has too many to write ("": it has not), before anything is allocated
std::string node_count_refusal(size_t angles, int sides, double bins, int k);

// Whether a model's value can be booked in a bin: finite, non-negative, at most the largest float (the bins and the
// EXR hold floats); gonio score refuses a values file with any other, and so does the Python module.
bool usable_model_value(double x);
// Whether `id` can name a model given as values (gonio score --id, the Python module's models): not empty, not
// "reference", no comma, quote or control character (the outputs' CSV and JSON hold it).
bool usable_model_id(const std::string& id);

// What nodes.json says of the nodes beside it (gonio nodes wrote it; gonio score reads it as data from outside:
// each field checked against what gonio nodes could have written, a StackError naming the field otherwise)
struct NodesFile {
    Stack stack;
    std::vector<double> theta_i;
    double dtheta = 0, dphi = 0;
    int k = 0, sides = 0;
    uint64_t nodes = 0;
    double phi_i = 0;   // the incident azimuth, degrees (nodes.json's phi_i, absent at 0)
};
NodesFile read_nodes_json(const std::string& dir);
// What gonio nodes writes into out (created): nodes.csv and nodes.npy (the nodes of bin_nodes, in its order) and
// nodes.json (f; stack_file: where the stack came from)
void write_nodes_files(const std::string& out, const std::string& stack_file, const NodesFile& f,
                       const std::vector<BinNode>& nodes);

inline ModelGrid grid_of(const std::vector<double>& theta_i, double dtheta, double dphi, double phi_i) {
    return {uint32_t(std::lround(90.0 / dtheta)), uint32_t(std::lround(360.0 / dphi)), dtheta, dphi, theta_i, phi_i};
}

// NumPy's .npy format 1.0 (numpy.lib.format) of rows x cols float64 in C order.
void write_npy_f8(const std::string& path, const std::vector<double>& data, size_t rows, size_t cols);
// The values file: one row per node, in nodes.csv's order, "r,g,b" (an optional header line r,g,b first); a value
// that is negative, NaN or infinite is refused (StackError: the file and line), nothing is clamped.
std::vector<glm::dvec3> read_values(const std::string& path);
// Values as .npy: shape (nodes, 3), float64 or float32, C order, little-endian (numpy.save of an array r,g,b).
std::vector<glm::dvec3> read_values_npy(const std::string& path);

}   // namespace gonio
