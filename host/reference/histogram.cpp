#include "histogram.h"
#include "statistics.h"

#include <algorithm>
#include <cmath>

namespace gonio {

double BinGrid::projected_solid_angle(uint32_t t) const {
    double lo = theta_lo(t) * M_PI / 180.0, hi = theta_hi(t) * M_PI / 180.0;
    double s_lo = std::sin(lo), s_hi = std::sin(hi);
    return 0.5 * (s_hi * s_hi - s_lo * s_lo) * dphi_deg * M_PI / 180.0;
}

uint32_t BinGrid::theta_bin(double theta_deg) const {
    return std::min<uint32_t>(uint32_t(std::max(0.0, theta_deg / dtheta_deg)), n_theta - 1);
}

uint32_t BinGrid::phi_bin(double phi_deg) const {
    long j = std::lround(std::floor(phi_deg / dphi_deg + 0.5));
    j %= long(n_phi);
    if (j < 0) j += n_phi;
    return uint32_t(j);
}

Slice make_slice(const SimResult& r, size_t angle, Side side, int cls) {
    return make_slice(r, r.angles.at(angle), side, cls);
}

Slice make_slice(const SimResult& r, const AngleResult& a, Side side, int cls) {
    BinGrid g(r);
    const size_t nb = size_t(g.n_theta) * g.n_phi;
    Slice s;
    s.f.assign(nb, glm::dvec3(0));
    s.se.assign(nb, glm::dvec3(0));
    s.sum.assign(nb, glm::dvec3(0));
    const double N = double(a.paths);
    if (uint32_t(side) >= r.n_sides) return s;   // an opaque stack has no transmission bins: nothing left that way
    for (uint32_t t = 0; t < g.n_theta; ++t) {
        const double omega = g.projected_solid_angle(t);
        for (uint32_t p = 0; p < g.n_phi; ++p) {
            const size_t b = size_t(t) * g.n_phi + p;
            for (int c = 0; c < kChannels; ++c) {
                double s1 = 0, s2 = 0;
                for (uint32_t k = 0; k < r.n_classes; ++k) {
                    if (cls >= 0 && int(k) != cls) continue;
                    size_t idx = ((size_t(k) * r.n_sides + side) * nb + b) * 6;
                    s1 += double(a.raw[idx + c]) / kFixedScale;
                    s2 += double(a.raw[idx + 3 + c]) / kFixedScale;
                }
                double mean = s1 / N;
                double var = N > 1 ? std::max(0.0, s2 / N - mean * mean) / (N - 1) : 0.0;
                s.sum[b][c] = mean;
                s.f[b][c] = mean / omega;
                s.se[b][c] = std::sqrt(var) / omega;
            }
        }
    }
    return s;
}

namespace {
// The relative standard errors of the bins above 1% of their slice's peak, per side and channel, sorted.
std::vector<double> relative_ses(const SimResult& r, const AngleResult& a) {
    std::vector<double> v;
    for (int side = 0; side < int(r.n_sides); ++side) {
        Slice s = make_slice(r, a, Side(side));
        for (int c = 0; c < kChannels; ++c) {
            double peak = 0;
            for (auto& x : s.f) peak = std::max(peak, x[c]);
            if (peak <= 0) continue;
            for (size_t b = 0; b < s.f.size(); ++b)
                if (s.f[b][c] > 0.01 * peak) v.push_back(s.se[b][c] / s.f[b][c]);
        }
    }
    std::sort(v.begin(), v.end());
    return v;
}
}   // namespace

double relative_se_quantile(const SimResult& r, const AngleResult& a, double q) {
    return quantile_of_sorted(relative_ses(r, a), q);
}

void summarise_relative_se(const SimResult& r, AngleResult& a) {
    const std::vector<double> v = relative_ses(r, a);
    a.worst_rse = quantile_of_sorted(v, 1.0);
    a.median_rse = quantile_of_sorted(v, 0.5);
    a.p90_rse = quantile_of_sorted(v, 0.9);
}

EnergyBook energy_book(const SimResult& r, size_t angle) {
    const AngleResult& a = r.angles.at(angle);
    EnergyBook e;
    const double N = double(a.paths);
    for (int side = 0; side < 2; ++side) {
        glm::dvec3 tot(0);
        for (const auto& v : make_slice(r, angle, Side(side)).sum) tot += v;
        (side == 0 ? e.reflected : e.transmitted) = tot;
    }
    for (int c = 0; c < kChannels; ++c) {
        e.absorbed[c] = double(a.energy[c]) / kEnergyScale / N;
        e.microfacet_loss[c] = double(a.energy[3 + c]) / kEnergyScale / N;
        e.truncated[c] = double(a.energy[6 + c]) / kEnergyScale / N;
        e.invalid[c] = double(a.energy[9 + c]) / kEnergyScale / N;
    }
    return e;
}

double median_relative_se(const SimResult& r, const AngleResult& a, int side) {
    if (a.paths < 2) return 0.0;
    Slice s = make_slice(r, a, Side(side));
    std::vector<double> rel;
    for (int c = 0; c < kChannels; ++c) {
        double peak = 0;
        for (auto& v : s.f) peak = std::max(peak, v[c]);
        if (peak <= 0) continue;
        for (size_t b = 0; b < s.f.size(); ++b)
            if (s.f[b][c] > 0.01 * peak) rel.push_back(s.se[b][c] / s.f[b][c]);
    }
    if (rel.empty()) return 0.0;
    std::nth_element(rel.begin(), rel.begin() + rel.size() / 2, rel.end());
    return rel[rel.size() / 2];
}

}   // namespace gonio
