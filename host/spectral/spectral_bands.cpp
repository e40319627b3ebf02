// spectral_bands.cpp: see spectral_bands.h.
#include "spectral_bands.h"
#include "spectral_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace gonio {

size_t SpectralBands::count() const { return size_t(std::llround((last_nm - first_nm) / width_nm)); }

void SpectralBands::check() const {
    const double n = (last_nm - first_nm) / width_nm;
    if (!(width_nm > 0) || std::fabs(n - std::round(n)) > 1e-9 || n < 3) {
        std::ostringstream w;
        w << width_nm;
        throw std::invalid_argument("the band width (" + w.str() + " nm) must divide " + std::to_string(int(first_nm)) +
                                    " to " + std::to_string(int(last_nm)) +
                                    " nm into at least 3 bands (for example 5, 10, 20, 40)");
    }
    if (points < 1 || points > kMaxPoints)
        throw std::invalid_argument(std::to_string(points) + " wavelengths per band: from 1 to " +
                                    std::to_string(kMaxPoints));
}

std::vector<std::array<double, 3>> xyz_weights(const SpectralBands& bands) {
    const SpectralTable& cmf = embedded_spectral_table("cie1931-2deg-cmf.csv");
    const SpectralTable& d65 = embedded_spectral_table("cie-d65.csv");
    auto integrand = [&](int c, double nm) { return cmf.at(size_t(c), nm) * d65.at(0, nm); };
    std::vector<std::array<double, 3>> w(bands.count());
    double y_total = 0;
    for (size_t b = 0; b < w.size(); ++b) {
        const double lo = bands.first_nm + double(b) * bands.width_nm, hi = lo + bands.width_nm;
        const int steps = int(std::lround(hi - lo));   // 1 nm trapezoids
        for (int c = 0; c < 3; ++c) {
            double s = 0;
            for (int i = 0; i < steps; ++i) {
                const double a = lo + (hi - lo) * i / steps, z = lo + (hi - lo) * (i + 1) / steps;
                s += 0.5 * (integrand(c, a) + integrand(c, z)) * (z - a);
            }
            w[b][size_t(c)] = s;
        }
        y_total += w[b][1];
    }
    for (auto& x : w)
        for (double& v : x) v /= y_total;
    return w;
}

namespace {

// q in proportion with the mean 1, the shares that would fall below `floor` held at it (the rest in proportion to
// what is left); a share of 0 is held at the floor.
std::vector<double> shares_with_floor(std::vector<double> q, double floor) {
    const size_t n = q.size();
    std::vector<bool> floored(n, false);
    for (bool changed = true; changed;) {
        changed = false;
        double free_weight = 0, free_share = double(n);
        for (size_t g = 0; g < n; ++g)
            if (floored[g])
                free_share -= floor;
            else
                free_weight += q[g];
        const double scale = free_weight > 0 ? free_share / free_weight : 0;
        for (size_t g = 0; g < n; ++g)
            if (!floored[g] && !(q[g] * scale >= floor)) floored[g] = changed = true;
        if (!changed)
            for (size_t g = 0; g < n; ++g) q[g] = floored[g] ? floor : q[g] * scale;
    }
    return q;
}

}   // namespace

std::vector<double> pass_shares(const SpectralBands& bands) {
    const size_t n = bands.count(), passes = (n + 2) / 3;
    std::vector<double> q(passes, 1.0);
    if (bands.pass_paths != SpectralBands::PassPaths::Weight) return q;
    const std::vector<std::array<double, 3>> w = xyz_weights(bands);
    for (size_t g = 0; g < passes; ++g) {
        q[g] = 0;
        for (size_t b = 3 * g; b < std::min(n, 3 * g + 3); ++b) q[g] += w[b][0] + w[b][1] + w[b][2];
    }
    return shares_with_floor(q, kPassShareFloor);
}

SpectralBands::PassPaths pass_paths_for(const SpectralBands& bands, double rse_target) {
    if (bands.pass_paths_chosen || !(rse_target > 0)) return bands.pass_paths;
    return SpectralBands::PassPaths::Weight;
}

const char* to_string(SpectralBands::PassPaths p) {
    switch (p) {
        case SpectralBands::PassPaths::Even:
            return "even";
        case SpectralBands::PassPaths::Weight:
            return "weight";
        case SpectralBands::PassPaths::Measured:
            return "measured";
    }
    return "?";
}

SpectralBands::PassPaths parse_pass_paths(const std::string& name) {
    for (SpectralBands::PassPaths p :
         {SpectralBands::PassPaths::Even, SpectralBands::PassPaths::Weight, SpectralBands::PassPaths::Measured})
        if (name == to_string(p)) return p;
    throw std::invalid_argument("expected even, weight or measured, got '" + name + "'");
}

std::vector<double> minimax_pass_shares(const std::vector<std::array<double, 3>>& a, double floor) {
    const size_t n = a.size();
    std::array<bool, 3> varies{};
    for (const std::array<double, 3>& g : a)
        for (int c = 0; c < 3; ++c) varies[size_t(c)] = varies[size_t(c)] || g[size_t(c)] > 0;
    std::vector<double> best(n, 1.0);
    if (!varies[0] && !varies[1] && !varies[2]) return best;
    auto shares = [&](const std::array<double, 3>& lambda) {
        std::vector<double> q(n);
        for (size_t g = 0; g < n; ++g)
            q[g] = std::sqrt(lambda[0] * a[g][0] + lambda[1] * a[g][1] + lambda[2] * a[g][2]);
        return shares_with_floor(q, floor);
    };
    auto variances = [&](const std::vector<double>& q) {
        std::array<double, 3> v{};
        for (size_t g = 0; g < n; ++g)
            for (int c = 0; c < 3; ++c) v[size_t(c)] += a[g][size_t(c)] / q[g];
        return v;
    };
    std::array<double, 3> lambda{};
    for (int c = 0; c < 3; ++c) lambda[size_t(c)] = varies[size_t(c)] ? 1.0 : 0.0;
    double least = INFINITY;
    for (int it = 0; it < 2000; ++it) {
        const std::vector<double> q = shares(lambda);
        const std::array<double, 3> v = variances(q);
        const double worst = std::max({v[0], v[1], v[2]});
        if (worst < least) {
            least = worst;
            best = q;
        }
        double sum = 0;
        for (int c = 0; c < 3; ++c) {
            lambda[size_t(c)] *= std::exp(0.5 * (v[size_t(c)] / worst - 1));
            sum += lambda[size_t(c)];
        }
        for (double& l : lambda) l /= sum;
    }
    return best;
}

std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz) {
    static constexpr double m[3][3] = {
        {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
    std::array<double, 3> rgb{};
    for (int r = 0; r < 3; ++r) rgb[size_t(r)] = m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2];
    return rgb;
}

}   // namespace gonio
