// colour_difference.h: how far apart two colours look: CIEDE2000 (CIE 142-2001, in CIELAB) and Delta E_ITP
// (ITU-R BT.2124-0, in ICtCp), from CIE 1931 XYZ under D65 with a perfect white reflector at Y = 1 (spectral_bands.h).
//
// Both need the colours' brightness against something: gonio gives them a bin's reflectance factor pi f (the bin
// seen beside a perfect white diffuser lit the same way, which has Y = 1): CIELAB's white is D65 at Y_n = 1, and
// Delta E_ITP takes Y = 1 as 100 cd/m^2 (BT.2408's reference white), so a specular peak of pi f = 100 is
// 10000 cd/m^2, the top of PQ. Above Y = 1, L* is above 100: CIEDE2000 extrapolates there (docs/SPECTRAL.md).
#pragma once

#include <array>

namespace gonio {

using Colour3 = std::array<double, 3>;

// CIELAB of XYZ against D65's white at Y = 1, from its chromaticity (0.3127, 0.3290) (CIE 015:2018, 8.2.1).
Colour3 xyz_to_lab(const Colour3& xyz);
// CIEDE2000 colour difference between two CIELAB colours, k_L = k_C = k_H = 1 (Sharma, Wu and Dalal 2005, eqs. 1-21).
double delta_e_2000(const Colour3& lab1, const Colour3& lab2);
// ICtCp (ITU-R BT.2100-2, PQ) of XYZ in cd/m^2.
Colour3 xyz_to_ictcp(const Colour3& xyz_cd_m2);
// Delta E_ITP (ITU-R BT.2124-0): 720 sqrt(dI^2 + dT^2 + dP^2), T = Ct / 2, P = Cp.
double delta_e_itp(const Colour3& ictcp1, const Colour3& ictcp2);

// sRGB's linear RGB (D65) to XYZ (IEC 61966-2-1): (1, 1, 1) is D65's white at Y = 1.
Colour3 linear_srgb_to_xyz(const Colour3& rgb);

// The two differences between colours given as XYZ reflectance factors (Y = 1: a perfect white diffuser).
struct ColourDifference {
    double de2000 = 0, de_itp = 0;
};
constexpr double kItpWhiteCdM2 = 100.0;   // the luminance Delta E_ITP gives Y = 1
ColourDifference colour_difference(const Colour3& xyz1, const Colour3& xyz2);

}   // namespace gonio
