// quadrature.h: Gauss-Legendre nodes and weights on [0, 1], for the host's and the tests' integrals.
#pragma once
#include <cmath>
#include <vector>

namespace gonio {

// n nodes x and weights w on [0, 1] (Newton on P_n from the Chebyshev guesses); exact for polynomials of degree
// up to 2n - 1.
inline void gauss_legendre_01(int n, std::vector<double>& x, std::vector<double>& w) {
    x.assign(n, 0.0);
    w.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            double p = n == 1 ? z : p1, pm1 = n == 1 ? 1.0 : p0;
            dp = n * (z * p - pm1) / (z * z - 1.0);
            double dz = p / dp;
            z -= dz;
            if (std::fabs(dz) < 1e-15) break;
        }
        x[i] = 0.5 * (1.0 - z);
        w[i] = 1.0 / ((1.0 - z * z) * dp * dp);   // 2 / ((1 - z^2) P_n'(z)^2), halved for [0, 1]
    }
}

}   // namespace gonio
