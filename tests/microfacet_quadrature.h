// microfacet_quadrature.h: integrals over a rough interface's microfacet normals, for the tests that hold the
// microsurfaces' closed forms and the walk's sampling against them (test_microsurface.cpp, test_microsurface_walk.cpp).
#pragma once
#include <glm/glm.hpp>

#include <cmath>

namespace microfacet_quadrature {

// The integral over the upper hemisphere of g(m) D(m) dm, D a distribution of roughness alpha (D(m, alpha) as the
// shaders' ggx_D and beckmann_D): the midpoint rule in s, tan theta_m = alpha s / (1 - s) (s in [0, 1): the peak at
// any alpha and GGX's long tail alike, the horizon itself never evaluated), and in phi.
template <class Dist, class G>
double over_microfacets(double alpha, Dist D, G g, int n_s = 3000, int n_phi = 720) {
    const double hs = 1.0 / n_s, hp = 2 * M_PI / n_phi;
    double sum = 0;
    for (int i = 0; i < n_s; ++i) {
        const double s = (i + 0.5) * hs, t = alpha * s / (1 - s), theta = std::atan(t);
        const double dtheta_ds = alpha / ((1 - s) * (1 - s) * (1 + t * t));
        double ring = 0;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * hp;
            const glm::vec3 m(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                              float(std::cos(theta)));
            ring += g(m) * double(D(m, float(alpha)));
        }
        sum += ring * hp * std::sin(theta) * dtheta_ds;
    }
    return sum * hs;
}

}   // namespace microfacet_quadrature
