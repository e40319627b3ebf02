// chi2.h: Pearson chi-square goodness-of-fit of a direction sampler against its density on the sphere.
// Equal-area cells in (cos theta, phi); expected counts by midpoint quadrature of the density on a
// sub-grid; cells with expected count below 5 are pooled; p-value from the regularised upper incomplete
// gamma function. (After Mitsuba's chi2 test and Jakob's "chi2" test in pbrt's test suite.)
#pragma once
#include "statistics.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace chi2 {

using gonio::gamma_q;   // host/core/statistics.h

struct Result {
    double p_value = 0;
    double chi2 = 0;
    int dof = 0;
    double pdf_integral = 0;   // quadrature of the density over the sphere (should be 1)
    std::string failure;   // non-empty: a sample landed where the density is zero, etc.
};

// sample(i) returns the i-th sampled direction; pdf(w) its solid-angle density.
inline Result test(const std::function<glm::vec3(int)>& sample, const std::function<double(glm::vec3)>& pdf,
                   int n_samples, int n_cos = 40, int n_phi = 80, int sub = 24) {
    Result r;
    const int nc = n_cos * n_phi;
    std::vector<double> observed(nc, 0), expected(nc, 0);
    auto cell = [&](glm::vec3 w) {
        double c = std::clamp(double(w.z), -1.0, 1.0);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * M_PI;
        int ic = std::min(n_cos - 1, int((c + 1) * 0.5 * n_cos));
        int ip = std::min(n_phi - 1, int(phi / (2 * M_PI) * n_phi));
        return ic * n_phi + ip;
    };
    for (int i = 0; i < n_samples; ++i) {
        glm::vec3 w = sample(i);
        if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z) ||
            std::fabs(glm::length(w) - 1) > 1e-3f) {
            r.failure = "sample " + std::to_string(i) + " is not a unit vector";
            return r;
        }
        observed[cell(w)] += 1;
    }
    const double dc = 2.0 / n_cos, dp = 2 * M_PI / n_phi;
    for (int ic = 0; ic < n_cos; ++ic)
        for (int ip = 0; ip < n_phi; ++ip) {
            double s = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    double c = -1 + (ic + (a + 0.5) / sub) * dc;
                    double phi = (ip + (b + 0.5) / sub) * dp;
                    double st = std::sqrt(std::max(0.0, 1 - c * c));
                    s += pdf(glm::vec3(float(st * std::cos(phi)), float(st * std::sin(phi)), float(c)));
                }
            double integral = s * dc * dp / (sub * sub);
            r.pdf_integral += integral;
            expected[ic * n_phi + ip] = integral * n_samples;
        }
    // pool cells with small expected counts
    std::vector<int> order(nc);
    for (int i = 0; i < nc; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pooled_obs = 0, pooled_exp = 0, chi = 0;
    int cells = 0;
    for (int i : order) {
        if (expected[i] == 0) {
            if (observed[i] > 0) {
                r.failure = "samples in a cell where the density integrates to zero (cell " + std::to_string(i) + ")";
                return r;
            }
            continue;
        }
        if (expected[i] < 5) {
            pooled_obs += observed[i];
            pooled_exp += expected[i];
            if (pooled_exp >= 5) {
                chi += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
                ++cells;
                pooled_obs = pooled_exp = 0;
            }
            continue;
        }
        chi += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++cells;
    }
    if (pooled_exp > 0) {
        chi += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++cells;
    }
    r.chi2 = chi;
    r.dof = cells - 1;
    r.p_value = r.dof > 0 ? gamma_q(r.dof / 2.0, chi / 2.0) : 1.0;
    return r;
}

}   // namespace chi2
