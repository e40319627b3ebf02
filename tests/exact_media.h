// exact_media.h: closed forms of light scattered by a plane-parallel medium under an index-matched smooth top (no
// refraction, no Fresnel), for the tests of scattering media. Conventions: mu_i, mu_o > 0 are the cosines of the
// incident and outgoing directions (both away from the surface), cos_scatter the cosine between the directions of
// propagation before and after the scattering event, phase functions normalised over the sphere (1/sr), f the BRDF
// without the cosine.
#pragma once
#include "quadrature.h"

#include <cmath>
#include <vector>

namespace exact_media {

// Single scattering in a slab of optical thickness tau and single-scattering albedo omega over a black, index-matched
// bottom: the collimated beam at optical depth t is exp(-t / mu_i); scattering there into the outgoing direction and
// leaving attenuated by exp(-t / mu_o), integrated over t in [0, tau]:
//   f_1 = omega p(cos) (1 - exp(-tau (1/mu_i + 1/mu_o))) / (mu_i + mu_o)   (Chandrasekhar 1960, ch. I; Hanrahan &
// Krueger 1993, eq. 20 without Fresnel factors).
inline double single_scattering_brdf(double mu_i, double mu_o, double phase_value, double tau, double omega) {
    return omega * phase_value * -std::expm1(-tau * (1.0 / mu_i + 1.0 / mu_o)) / (mu_i + mu_o);
}

// Chandrasekhar's H-function of isotropic scattering with albedo omega (Radiative Transfer, 1960, ch. V):
//   H(mu) = 1 + (omega / 2) mu H(mu) int_0^1 H(mu') / (mu + mu') dmu',
// solved in its equivalent form 1 / H(mu) = sqrt(1 - omega) + (omega / 2) int_0^1 mu' H(mu') / (mu + mu') dmu'
// (ch. V, eq. 31), on Gauss-Legendre nodes, iterating H <- sqrt(H T(H)) with T the right-hand side's inverse:
// for omega = 1 the plain iteration T swaps c H and H / c forever, the geometric mean removes that mode. Evaluated
// anywhere through the same equation.
class HFunction {
public:
    explicit HFunction(double omega, int nodes = 96) : omega_(omega) {
        gonio::gauss_legendre_01(nodes, x_, w_);
        h_.assign(nodes, 1.0);
        for (int it = 0; it < 10000; ++it) {
            double change = 0;
            std::vector<double> next(nodes);
            for (int i = 0; i < nodes; ++i) next[i] = std::sqrt(h_[i] * (*this)(x_[i]));
            for (int i = 0; i < nodes; ++i) change = std::max(change, std::fabs(next[i] - h_[i])), h_[i] = next[i];
            if (change < 1e-15) break;
        }
    }
    double operator()(double mu) const {
        double s = 0;
        for (size_t j = 0; j < x_.size(); ++j) s += w_[j] * x_[j] * h_[j] / (mu + x_[j]);
        return 1.0 / (std::sqrt(1.0 - omega_) + 0.5 * omega_ * s);
    }
    // int_0^1 H(mu) dmu by the same quadrature
    double integral() const {
        double s = 0;
        for (size_t j = 0; j < x_.size(); ++j) s += w_[j] * h_[j];
        return s;
    }

private:
    double omega_;
    std::vector<double> x_, w_, h_;
};

// The semi-infinite medium of isotropic scattering, every order of scattering (Chandrasekhar 1960, ch. IV, eq. 43
// for the diffuse reflection of a collimated beam): f = omega / (4 pi) H(mu_i) H(mu_o) / (mu_i + mu_o); its
// directional albedo is 1 - H(mu_i) sqrt(1 - omega).
inline double semi_infinite_isotropic_brdf(const HFunction& H, double mu_i, double mu_o, double omega) {
    return omega / (4 * M_PI) * H(mu_i) * H(mu_o) / (mu_i + mu_o);
}

}   // namespace exact_media
