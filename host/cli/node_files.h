// node_files.h: what `gonio nodes` writes and `gonio score` reads back: the format number of nodes.json, and the grid
// of bins its nodes lie in.
#pragma once
#include "model_evaluator.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace gonio {

constexpr int kNodesFormat = 1;   // nodes.json's "gonio_nodes"

inline ModelGrid grid_of(const std::vector<double>& theta_i, double dtheta, double dphi) {
    return {uint32_t(std::lround(90.0 / dtheta)), uint32_t(std::lround(360.0 / dphi)), dtheta, dphi, theta_i};
}

}   // namespace gonio
