#include "bin_nodes.h"
#include "quadrature.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gonio {

std::vector<BinNode> bin_nodes(const ModelGrid& g, int sides, int k) {
    std::vector<double> x, w;
    gauss_legendre_01(k, x, w);
    const double dt = g.dtheta_deg * M_PI / 180, dp = g.dphi_deg * M_PI / 180;
    std::vector<BinNode> out;
    out.reserve(g.theta_i_deg.size() * size_t(sides) * g.n_theta * g.n_phi * size_t(k * k));
    for (uint32_t a = 0; a < g.theta_i_deg.size(); ++a) {
        const double ti = g.theta_i_deg[a] * M_PI / 180, pi = g.phi_i_deg * M_PI / 180;
        const glm::dvec3 l(std::sin(ti) * std::cos(pi), std::sin(ti) * std::sin(pi), std::cos(ti));
        for (uint32_t side = 0; side < uint32_t(sides); ++side)
            for (uint32_t t = 0; t < g.n_theta; ++t) {
                const double s0 = std::pow(std::sin(t * dt), 2), s1 = std::pow(std::sin((t + 1) * dt), 2);
                for (uint32_t p = 0; p < g.n_phi; ++p)
                    for (int i = 0; i < k; ++i) {
                        const double s = s0 + (s1 - s0) * x[size_t(i)];   // sin^2 theta
                        const double st = std::sqrt(s), ct = std::sqrt(std::max(0.0, 1.0 - s));
                        for (int j = 0; j < k; ++j) {
                            const double phi = (double(p) - 0.5 + x[size_t(j)]) * dp;
                            const glm::dvec3 v(st * std::cos(phi), st * std::sin(phi), side ? -ct : ct);
                            out.push_back({a, side, t * g.n_phi + p, l, v, w[size_t(i)] * w[size_t(j)]});
                        }
                    }
            }
    }
    return out;
}

ModelSlices slices_from_node_values(const std::string& id, const ModelGrid& g, int sides, int k,
                                    const std::vector<glm::dvec3>& values) {
    const std::vector<BinNode> nodes = bin_nodes(g, sides, k);
    if (values.size() != nodes.size())
        throw std::invalid_argument(std::to_string(values.size()) + " values for " + std::to_string(nodes.size()) +
                                    " nodes");
    ModelSlices ms;
    ms.id = id;
    const size_t bins = size_t(g.n_theta) * g.n_phi;
    ms.f.assign(g.theta_i_deg.size(), std::vector<glm::dvec3>(bins, glm::dvec3(0.0)));
    if (sides == 2) ms.t.assign(g.theta_i_deg.size(), std::vector<glm::dvec3>(bins, glm::dvec3(0.0)));
    for (size_t n = 0; n < nodes.size(); ++n) {
        const BinNode& b = nodes[n];
        (b.side ? ms.t : ms.f)[b.angle][b.bin] += b.weight * values[n];
    }
    return ms;
}

}   // namespace gonio
