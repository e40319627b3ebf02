// model_reciprocity.cpp: the direction pairs and the asymmetry of a model's values at them (model_reciprocity.h).
#include "model_reciprocity.h"

#include <algorithm>
#include <cmath>

namespace gonio {

namespace {

constexpr double kThetas[] = {5, 20, 35, 50, 65, 80, 88};
constexpr double kPhis[] = {0, 60, 120, 180};

struct Pair {
    double theta_l, theta_v, phi;
};

std::vector<Pair> pairs() {
    std::vector<Pair> p;
    for (double a : kThetas)
        for (double b : kThetas)
            for (double phi : kPhis) p.push_back({a, b, phi});
    return p;
}

glm::vec3 direction(double theta_deg, double phi_deg) {
    const double t = theta_deg * M_PI / 180, p = phi_deg * M_PI / 180;
    return glm::vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t)));
}

}   // namespace

std::vector<glm::vec3> reciprocity_directions() {
    std::vector<glm::vec3> d;
    for (const Pair& p : pairs()) {
        const glm::vec3 l = direction(p.theta_l, 0.0), v = direction(p.theta_v, p.phi);
        d.insert(d.end(), {l, v, v, l});
    }
    return d;
}

ModelAsymmetry measure_asymmetry(const std::vector<glm::dvec3>& f) {
    const std::vector<Pair> ps = pairs();
    ModelAsymmetry a;
    auto usable = [](const glm::dvec3& x) {
        return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z) && x.x >= 0 && x.y >= 0 && x.z >= 0;
    };
    double largest = 0;
    for (size_t k = 0; k < ps.size() && 2 * k + 1 < f.size(); ++k)
        if (usable(f[2 * k]) && usable(f[2 * k + 1]))
            for (int c = 0; c < 3; ++c) largest = std::max({largest, f[2 * k][c], f[2 * k + 1][c]});
    for (size_t k = 0; k < ps.size() && 2 * k + 1 < f.size(); ++k) {
        const glm::dvec3 &x = f[2 * k], &y = f[2 * k + 1];
        if (!usable(x) || !usable(y)) {
            ++a.non_finite;
            continue;
        }
        ++a.pairs;
        for (int c = 0; c < 3; ++c) {
            const double mean = 0.5 * (x[c] + y[c]);
            if (mean <= 1e-6 * largest) continue;
            ++a.compared;
            const double r = std::fabs(x[c] - y[c]) / mean;
            if (r > a.worst) {
                a.worst = r;
                a.theta_l = ps[k].theta_l;
                a.theta_v = ps[k].theta_v;
                a.phi = ps[k].phi;
            }
        }
    }
    return a;
}

}   // namespace gonio
