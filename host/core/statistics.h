// statistics.h: the distribution functions gonio's tests of agreement need (chi-square and normal tails).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

namespace gonio {

// Regularised upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a) (Numerical Recipes 3rd ed. 6.2: the series
// for x < a + 1, else the Lentz continued fraction). For a chi-square statistic X with k degrees of freedom,
// P(chi2_k >= X) = Q(k / 2, X / 2).
inline double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double gln = std::lgamma(a);
    if (x < a + 1) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int n = 0; n < 100000; ++n) {
            ap += 1;
            del *= x / ap;
            sum += del;
            if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(-x + a * std::log(x) - gln));
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::fabs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::fabs(del - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - gln) * h;
}

// P(chi2_k >= x), the p-value of a chi-square statistic x with k degrees of freedom.
inline double chi2_p_value(double x, double k) { return k > 0 ? gamma_q(0.5 * k, 0.5 * x) : 1.0; }

// P(|Z| >= |z|) for a standard normal Z: the two-sided p-value of a z statistic.
inline double normal_two_sided_p(double z) { return std::erfc(std::fabs(z) / std::sqrt(2.0)); }

// The z with P(Z >= z) = p for a standard normal Z (0 < p < 1): bisection on erfc, to 1e-12.
inline double normal_upper_quantile(double p) {
    double lo = -40, hi = 40;
    for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// The nearest-rank quantile q of v (q = 1: the largest): the smallest value with at least a fraction q of the values
// at or below it; 0 for no values.
inline double quantile_of_sorted(const std::vector<double>& v, double q) {
    if (v.empty()) return 0.0;
    const size_t k = size_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(v.size())));
    return v[std::min(v.size(), std::max<size_t>(k, 1)) - 1];
}
inline double nearest_rank_quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return quantile_of_sorted(v, q);
}

}   // namespace gonio
