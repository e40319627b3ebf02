// bin_nodes.h: where to evaluate a model given as numbers, not code (gonio nodes / gonio score): quadrature nodes
// (l, v, weight) per bin such that the bin's average of f over projected solid angle is sum of weight x f(l, v).
// Conventions (docs/PHYSICS.md): z the stack normal, directions away from the surface, l = (sin theta_i cos phi_i,
// sin theta_i sin phi_i, cos theta_i) (phi_i: the grid's, 0 by default); v.z < 0 on the transmission side; f excludes the cosine; bins as the reference's (theta bins
// [t dtheta, (t + 1) dtheta], phi bins centred on p dphi, index t * n_phi + p).
#pragma once
#include "model_evaluator.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace gonio {

struct BinNode {
    uint32_t angle, side, bin;   // incident-angle index, 0 reflection / 1 transmission, t * n_phi + p
    glm::dvec3 l, v;
    double weight;   // the node's share of its bin's average (the weights of a bin sum to 1)
};

// k x k Gauss-Legendre nodes per bin in (sin^2 theta, phi), in which the projected solid angle is uniform
// (cos theta d omega = d(sin^2 theta) dphi / 2), so f = 1 gives 1 in every bin; exact for f polynomial of degree
// 2k - 1 in each. Angle by angle, side by side, bin by bin, node by node (the order of nodes.csv).
std::vector<BinNode> bin_nodes(const ModelGrid& g, int sides, int k);

// A model's slices from its values at bin_nodes(g, sides, k), in that order (RGB per node).
ModelSlices slices_from_node_values(const std::string& id, const ModelGrid& g, int sides, int k,
                                    const std::vector<glm::dvec3>& values);

}   // namespace gonio
