// spectral_bands.h: the wavelength bands of a spectral run (--spectral, --bands W: 380 to 780 nm in bands W nm wide,
// each evaluated at its centre) and how they turn into colour: CIE 1931 XYZ under D65, normalised so that a perfect
// white reflector has Y = 1, and linear sRGB (IEC 61966-2-1).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace gonio {

struct SpectralBands {
    double first_nm = 380.0, last_nm = 780.0, width_nm = 10.0;

    size_t count() const;   // (last - first) / width bands; width must divide the range (checked: check())
    double centre_nm(size_t b) const { return first_nm + (double(b) + 0.5) * width_nm; }
    // Throws std::invalid_argument where the width does not divide 380-780 nm into at least 3 bands.
    void check() const;
};

// Per band, its weight in X, Y and Z: the integral over the band of xbar, ybar, zbar times D65 (1 nm steps,
// trapezoids), divided by the integral of ybar times D65 over all the bands: a spectrum of ones has Y = 1.
std::vector<std::array<double, 3>> xyz_weights(const SpectralBands& bands);

// Linear sRGB from XYZ (IEC 61966-2-1's matrix): D65's white (0.9505, 1, 1.089) gives (1, 1, 1).
std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz);

}   // namespace gonio
