// model_quadrature.h: a model's directional albedo by quadrature (in half-vector space, or the midpoint rule over the
// hemisphere), independent of models.comp (through the CPU twin, model_value_cpu), for the tests of the bin integration and the energy claims.
#pragma once
#include "models.h"
#include "stack_gpu.h"

#include <glm/glm.hpp>
#include <cmath>
#include <functional>

namespace gonio {

// The integral of f(v) cos(theta_v) dv over the hemisphere = the integral over m of f(v(m)) v.z 4 (l.m) dm,
// v = reflect(l, m), with tan(theta_m) = a (e^(L u) - 1), u in (0, 1), L = ln(1e4 / a + 1): steps far finer than
// a near the mirror direction (lobes as narrow as a are resolved), a few percent in the tail. nu x nphi nodes;
// f takes the reflected direction v (float, normalised) and returns RGB.
template <class F>
glm::dvec3 half_vector_quadrature(const F& f, glm::dvec3 l, double a, int nu, int nphi) {
    const double L = std::log(1e4 / a + 1);
    glm::dvec3 acc(0);
    for (int i = 0; i < nu; ++i) {
        double u = (i + 0.5) / nu;
        double tan_m = a * (std::exp(L * u) - 1);
        double tm = std::atan(tan_m);
        double dtm = a * L * std::exp(L * u) / (1 + tan_m * tan_m);   // d theta_m / du
        for (int j = 0; j < nphi; ++j) {
            double pm = (j + 0.5) / nphi * 2 * M_PI;
            glm::dvec3 m(std::sin(tm) * std::cos(pm), std::sin(tm) * std::sin(pm), std::cos(tm));
            double lm = glm::dot(l, m);
            if (lm <= 0) continue;
            glm::dvec3 v = 2 * lm * m - l;
            if (v.z <= 0) continue;
            acc += glm::dvec3(f(glm::vec3(glm::normalize(v)))) * (v.z * 4.0 * lm * std::sin(tm) * dtm);
        }
    }
    return acc * (1.0 / nu) * (2 * M_PI / nphi);
}

// The midpoint rule over the upper hemisphere of f(w) cos(theta) d omega, N x N nodes in (theta, phi): a directional
// albedo from the light's side (w = v) or the viewer's (w = l)
inline glm::dvec3 hemisphere_integral(const std::function<glm::dvec3(glm::vec3)>& f, int N) {
    glm::dvec3 e(0.0);
    for (int a = 0; a < N; ++a)
        for (int b = 0; b < N; ++b) {
            const double th = (a + 0.5) / N * M_PI / 2, ph = (b + 0.5) / N * 2 * M_PI;
            const glm::vec3 w(float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)),
                              float(std::cos(th)));
            e += f(w) * (std::cos(th) * std::sin(th));
        }
    return e * ((M_PI / 2 / N) * (2 * M_PI / N));
}

// A model's directional albedo at theta_i: the quadrature above of its f (model_value_cpu). t_side adds the
// transmitted lobe, drawn as the mirror lobe flipped through the surface plane, at the flipped v with the same
// weights.
inline glm::dvec3 albedo_by_quadrature(size_t model, const Stack& s, double theta_i_deg, double a, bool t_side, int nu,
                                       int nphi) {
    double ti = theta_i_deg * M_PI / 180;
    glm::dvec3 l(std::sin(ti), 0, std::cos(ti));
    const StackGpu sg = pack_stack(s);
    return half_vector_quadrature(
        [&](glm::vec3 vf) {
            glm::dvec3 f = model_value_cpu(model, sg, glm::vec3(l), vf);
            if (t_side) f += model_value_cpu(model, sg, glm::vec3(l), glm::vec3(vf.x, vf.y, -vf.z));
            return f;
        },
        l, a, nu, nphi);
}

}   // namespace gonio
