// histogram.h: from the raw fixed-point sums to calibrated BRDF/BTDF bin averages with standard errors.
//
// A bin's value is the bin average of f (1/sr): F = S1 / (N * Omega), with S1 the summed exit throughput of
// the N paths in the bin and Omega = integral over the bin of cos(theta) dOmega (the bin's exact projected
// solid angle, (sin^2 theta_hi - sin^2 theta_lo) / 2 * dphi). Its standard error is that of a mean of N
// per-path contributions X (X = w for paths in the bin, 0 otherwise):
// se = sqrt((S2/N - (S1/N)^2) / (N - 1)) / Omega.
#pragma once
#include "reference.h"

#include <glm/glm.hpp>
#include <vector>

namespace gonio {

struct BinGrid {
    uint32_t n_theta, n_phi;
    double dtheta_deg, dphi_deg;
    explicit BinGrid(const SimResult& r)
        : n_theta(r.n_theta), n_phi(r.n_phi), dtheta_deg(r.options.dtheta_deg), dphi_deg(r.options.dphi_deg) {}
    double theta_lo(uint32_t t) const { return t * dtheta_deg; }
    double theta_hi(uint32_t t) const { return (t + 1) * dtheta_deg; }
    double phi_lo(uint32_t p) const { return (p - 0.5) * dphi_deg; }   // bins centred on p * dphi
    double phi_hi(uint32_t p) const { return (p + 0.5) * dphi_deg; }
    double projected_solid_angle(uint32_t t) const;
    // bin containing the direction (theta, phi) in degrees on one side
    uint32_t theta_bin(double theta_deg) const;
    uint32_t phi_bin(double phi_deg) const;
};

enum Side { kReflection = 0, kTransmission = 1 };

struct Slice {   // one incident angle, one side, n_theta * n_phi bins (theta-major)
    std::vector<glm::dvec3> f;   // bin average of f, 1/sr
    std::vector<glm::dvec3> se;   // its standard error
    std::vector<glm::dvec3> sum;   // S1 / N: fraction of the incident energy leaving through the bin
};

// cls = -1: all path classes together; 0, 1, 2: one class (needs --orders).
Slice make_slice(const SimResult& r, size_t angle, Side side, int cls = -1);
Slice make_slice(const SimResult& r, const AngleResult& a, Side side, int cls = -1);

struct EnergyBook {   // fractions of the incident energy, per channel
    glm::dvec3 reflected{0}, transmitted{0}, absorbed{0}, microfacet_loss{0}, truncated{0};
    glm::dvec3 invalid{0};   // paths that booked a non-finite number (walk.glsl path_is_finite): a bug if > 0
    glm::dvec3 sum() const { return reflected + transmitted + absorbed + microfacet_loss + truncated + invalid; }
};
EnergyBook energy_book(const SimResult& r, size_t angle);

// The relative standard errors of the bins of one angle whose value is above 1% of their slice's peak (per side
// and channel): the quantile q of them (q = 1: the largest; the nearest-rank quantile); 0 if nothing left the stack.
double relative_se_quantile(const SimResult& r, const AngleResult& a, double q);
inline double worst_relative_se(const SimResult& r, const AngleResult& a) { return relative_se_quantile(r, a, 1.0); }
// Sets a's worst_rse, median_rse and p90_rse.
void summarise_relative_se(const SimResult& r, AngleResult& a);

// Median relative standard error over the bins of one side whose value is above 1% of the peak of their
// channel (the bins that make the picture); 0 when nothing reached that side.
double median_relative_se(const SimResult& r, const AngleResult& a, int side);

}   // namespace gonio
