// rgb_uplift.h: a linear sRGB value turned into a smooth spectrum in [0, 1] (spectral upsampling), by the method of
// W. Jakob and J. Hanika, "A Low-Dimensional Function Space for Efficient Spectral Upsampling", Computer Graphics
// Forum 38(2), 2019 (Eurographics): what a spectral run (docs/SPECTRAL.md) gives a layer key that a stack file
// gives per RGB channel (a Lambertian albedo, a medium's transmittance exp(-optical_depth)).
//
// The spectrum (the paper's eq. 3 and 4): s(lambda) = S(c0 u^2 + c1 u + c2), with the sigmoid
//     S(x) = 1/2 + x / (2 sqrt(1 + x^2)),
// which maps every quadratic into (0, 1). gonio keeps the coefficients in the normalised wavelength
//     u = (lambda - 360 nm) / (830 nm - 360 nm)
// (the authors' own optimiser's conditioning, pbrt-v4 src/pbrt/cmd/rgb2spec_opt.cpp at commit
// 0dc9e4fcd9caf2119b302dcc521d119756c78f8f); SigmoidSpectrum::per_nm() converts them to the paper's (and pbrt's
// tables') polynomial in lambda in nm.
//
// The coefficients of a colour minimise its CIE76 difference (the paper's eq. 6: the Euclidean distance in CIELAB)
// from the colour of s under D65 (Levenberg-Marquardt on the three coefficients, from the grey of the same luminance
// and by continuation along the line from that grey to the colour). The colour of a reflectance s is gonio's, the
// one a spectral run reports at 1 nm bands: X, Y, Z = sum over the 1 nm bands from 380 to 780 nm of s at the band's
// centre times its xyz_weights (CIE 1931 2-degree, D65, Y = 1 for s = 1), linear sRGB by xyz_to_linear_srgb, each
// channel divided by that of s = 1 (white balance: the constant spectrum v is the grey (v, v, v) exactly; unbalanced,
// s = 1 is (1, 1, 1) within 2e-4: uplift_white_rgb()). CIELAB's white is that of s = 1.
//
// A grey (three equal channels) gives the constant spectrum exactly (c0 = c1 = 0; 0 and 1 as c2 = -inf and +inf).
// Any other colour is reached within kUpliftMaxDeltaE or refused (RgbUplift::reached false, with the closest colour
// and its difference): a colour no smooth spectrum in (0, 1) has (outside the reflectances' gamut, or at its edge,
// such as a channel at exactly 0 or 1 beside others that are not) is never approximated silently.
#pragma once

#include <array>
#include <string>

namespace gonio {

// The sigmoid S of the paper's eq. 4, exact in the tails (no cancellation for x far below 0).
double uplift_sigmoid(double x);

struct SigmoidSpectrum {
    std::array<double, 3> c{0.0, 0.0, 0.0};   // c0 u^2 + c1 u + c2, u the normalised wavelength (see above)
    static constexpr double kFirstNm = 360.0, kLastNm = 830.0;
    double at(double nm) const;   // s(lambda), in [0, 1]
    // The coefficients of the same quadratic in lambda in nm: s(lambda) = S(a lambda^2 + b lambda + c).
    std::array<double, 3> per_nm() const;
};

constexpr double kUpliftMaxDeltaE = 1e-3;   // CIE76: a colour reached closer than this is reached

struct RgbUplift {
    std::array<double, 3> rgb{};   // the colour asked for (linear sRGB)
    SigmoidSpectrum spectrum;
    std::array<double, 3> rgb_reached{};   // the colour of the spectrum (white balanced, see above)
    double delta_e76 = 0;   // between rgb and rgb_reached
    bool grey = false;   // three equal channels: the constant spectrum
    bool reached = false;   // delta_e76 < kUpliftMaxDeltaE (a grey always)
    int iterations = 0;   // Levenberg-Marquardt steps taken, all continuation stages together
};

// The spectrum of a linear sRGB reflectance colour, each channel in [0, 1] (std::invalid_argument outside, NaN
// included). Check reached: where false, the spectrum is the closest the method found, not the colour.
RgbUplift uplift_rgb(const std::array<double, 3>& rgb);

// The colour of a reflectance spectrum as uplift_rgb sees it (white balanced linear sRGB, see above).
std::array<double, 3> uplift_colour(const SigmoidSpectrum& s);

// Linear sRGB of s = 1 at the 1 nm bands, not balanced: how far gonio's colour of a white is from (1, 1, 1).
std::array<double, 3> uplift_white_rgb();

// "Jakob & Hanika 2019 ..." : the method in one line, for summaries.
extern const char* const kUpliftMethod;

}   // namespace gonio
