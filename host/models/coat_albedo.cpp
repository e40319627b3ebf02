#include "coat_albedo.h"
#include "model_twin.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace gonio {

std::vector<float> coat_albedo_table(const Stack& s) {
    // E(mu) = integral of f_r0(l, v) cos(theta_v) dv, by quadrature in half-vector space (v = reflect(l, m),
    // dv = 4 (l.m) dm) with tan(theta_m) = a (e^(L u) - 1) to resolve narrow lobes, at the table's nodes of mu.
    StackGpu sg = pack_stack(s);
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    const double a = p.alpha0, L = std::log(1e4 / a + 1);
    const int NU = 600, NP = 96;
    std::vector<float> table(COAT_ALBEDO_NODES);
    // l lies in the xz-plane, so the phi nodes j and NP - 1 - j give the same value: half of them, twice; the
    // nodes of mu on all cores (this runs on the host before every model evaluation)
    std::atomic<int> next{0};
    auto work = [&] {
        for (int i; (i = next++) < int(COAT_ALBEDO_NODES);) {
            double mu = std::max(double(coat_albedo_node_mu(uint(i))), 1e-3);
            glm::dvec3 l(std::sqrt(1 - mu * mu), 0, mu);
            double acc = 0;
            for (int k = 0; k < NU; ++k) {
                double u = (k + 0.5) / NU, tan_m = a * (std::exp(L * u) - 1), tm = std::atan(tan_m);
                double dtm = a * L * std::exp(L * u) / (1 + tan_m * tan_m);
                for (int j = 0; j < NP / 2; ++j) {
                    double pm = (j + 0.5) / NP * 2 * M_PI;
                    glm::dvec3 m(std::sin(tm) * std::cos(pm), std::sin(tm) * std::sin(pm), std::cos(tm));
                    double lm = glm::dot(l, m);
                    if (lm <= 0) continue;
                    glm::dvec3 v = 2 * lm * m - l;
                    if (v.z <= 0) continue;
                    acc += 2 * top_reflection(glm::vec3(l), glm::vec3(glm::normalize(v)), p.alpha0, p.eta) * v.z * 4 *
                           lm * std::sin(tm) * dtm;
                }
            }
            table[i] = float(std::min(1.0, acc / NU * 2 * M_PI / NP));
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::max(1u, std::thread::hardware_concurrency()); ++t) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
    return table;
}

}   // namespace gonio
