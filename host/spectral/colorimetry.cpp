// colorimetry.cpp: see colorimetry.h.
#include "colorimetry.h"
#include "spectral_table.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gonio {

namespace {

const SpectralTable& cmf() { return embedded_spectral_table("cie1931-2deg-cmf.csv"); }

// (l - w) x (c - w): its sign says on which side of the ray from w through c the point l lies
double side(Chromaticity l, Chromaticity c, Chromaticity w) {
    return (l.x - w.x) * (c.y - w.y) - (l.y - w.y) * (c.x - w.x);
}

}   // namespace

Chromaticity spectral_locus(double nm) {
    const SpectralTable& t = cmf();
    const double X = t.at(0, nm), Y = t.at(1, nm), Z = t.at(2, nm), s = X + Y + Z;
    return {X / s, Y / s};
}

double dominant_wavelength(Chromaticity c, Chromaticity w) {
    const SpectralTable& t = cmf();
    const double first = std::ceil(t.first_nm()), last = std::floor(t.last_nm());
    Chromaticity prev = spectral_locus(first);
    for (double nm = first + 1; nm <= last; nm += 1) {
        const Chromaticity l = spectral_locus(nm);
        const double a = side(prev, c, w), b = side(l, c, w);
        const bool same_way = (l.x - w.x) * (c.x - w.x) + (l.y - w.y) * (c.y - w.y) > 0;
        if (same_way && ((a <= 0 && b > 0) || (a >= 0 && b < 0))) return nm - 1 + a / (a - b);
        prev = l;
    }
    throw std::invalid_argument("the chromaticity (" + std::to_string(c.x) + ", " + std::to_string(c.y) +
                                ") is a purple: it has no dominant wavelength on the spectral locus");
}

const std::array<double, 3>& srgb_dominant_wavelengths() {
    static const std::array<double, 3> nm{dominant_wavelength(kSrgbPrimaries[0]),
                                          dominant_wavelength(kSrgbPrimaries[1]),
                                          dominant_wavelength(kSrgbPrimaries[2])};
    return nm;
}

}   // namespace gonio
