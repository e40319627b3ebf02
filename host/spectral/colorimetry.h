// colorimetry.h: what gonio takes from CIE colorimetry: the CIE 1931 2-degree observer's colour-matching functions
// (data/spectra/cie1931-2deg-cmf.csv), chromaticities, and the sRGB primaries (IEC 61966-2-1) with their dominant
// wavelengths, where the RGB reduction of a measured material reads its n and k (measured_materials.h).
#pragma once

#include <array>

namespace gonio {

struct Chromaticity {
    double x = 0, y = 0;
};

// IEC 61966-2-1 (sRGB): the primaries' chromaticities, red, green, blue, and the white point D65.
constexpr std::array<Chromaticity, 3> kSrgbPrimaries{{{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}};
constexpr Chromaticity kD65White{0.3127, 0.3290};

// The chromaticity of monochromatic light of wavelength nm (the spectral locus), from the colour-matching functions
// linearly interpolated; nm in [360, 830].
Chromaticity spectral_locus(double nm);

// The dominant wavelength of a colour of chromaticity c seen against the white w: where the ray from w through c
// meets the spectral locus (CIE 015:2018, 9.1), found on the locus at 1 nm steps and interpolated between them.
// Throws std::invalid_argument for a purple (the ray meets the line of purples, not the locus).
double dominant_wavelength(Chromaticity c, Chromaticity w = kD65White);

// The dominant wavelengths of the sRGB primaries red, green, blue against D65, computed once (about 611, 549 and
// 464 nm).
const std::array<double, 3>& srgb_dominant_wavelengths();

}   // namespace gonio
