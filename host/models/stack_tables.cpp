#include "coat_albedo.h"
#include "model_twin.h"

#include <algorithm>

namespace gonio {

std::vector<float> coat_albedo_table(const Stack& s) { return coat_albedo_table(pack_stack(s)); }

std::vector<float> coat_albedo_table(const StackGpu& sg) {
    // E_coat(mu) = the integral of f_r0(l, v) cos(theta_v) dv over the hemisphere (common.glsl's top_reflection:
    // dielectric Fresnel, GGX D, height-correlated G2), at the table's nodes of mu: the FGD of the coat's interface
    // with G2, by gonio's one quadrature of an interface's albedo (models/fgd_quadrature.glsl, which Belcour's
    // tables also call). mu = 0 is its limit mu -> 0+. Clamped to 1, so that
    // 1 - E_coat, the base's weight, is never negative.
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    std::vector<float> table(COAT_ALBEDO_NODES);
    for (uint i = 0; i < COAT_ALBEDO_NODES; ++i)
        table[i] = std::min(
            1.0f,
            fgd_quadrature(sg.layers[0], coat_albedo_node_mu(i), p.alpha0, true, FGD_NODES_THETA, FGD_NODES_PHI).x);
    return table;
}

}   // namespace gonio
