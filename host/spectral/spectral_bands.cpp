// spectral_bands.cpp: see spectral_bands.h.
#include "spectral_bands.h"
#include "spectral_table.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gonio {

size_t SpectralBands::count() const { return size_t(std::llround((last_nm - first_nm) / width_nm)); }

void SpectralBands::check() const {
    const double n = (last_nm - first_nm) / width_nm;
    if (!(width_nm > 0) || std::fabs(n - std::round(n)) > 1e-9 || n < 3)
        throw std::invalid_argument("--bands " + std::to_string(width_nm) + ": the band width must divide " +
                                    std::to_string(int(first_nm)) + " to " + std::to_string(int(last_nm)) +
                                    " nm into at least 3 bands (for example 5, 10, 20, 40)");
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

std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz) {
    static constexpr double m[3][3] = {
        {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
    std::array<double, 3> rgb{};
    for (int r = 0; r < 3; ++r) rgb[size_t(r)] = m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2];
    return rgb;
}

}   // namespace gonio
