// measured_materials.h: the conductors a stack can name (`material = "Au"`), their measured n(lambda) and k(lambda)
// (data/spectra/, each file with its source and licence), and how an RGB run reduces them to three channels.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace gonio {

struct MeasuredConductor {
    const char* name;   // what a stack writes: "Au"
    const char* file;   // data/spectra/ file with columns n, k
    const char* reference;   // whose measurement
};

const std::vector<MeasuredConductor>& measured_conductors();
const MeasuredConductor* find_measured_conductor(std::string_view name);   // nullptr: no such material
std::string measured_conductor_names();   // "Au, Ag, Cu, Al"

// n(lambda) and k(lambda) of a measured conductor, interpolated linearly in wavelength; throws std::out_of_range
// outside its table.
double measured_n(const MeasuredConductor& m, double nm);
double measured_k(const MeasuredConductor& m, double nm);

// The RGB reduction of a measured conductor (an RGB run of a stack that names one): n and k at the dominant
// wavelengths of the sRGB primaries against D65, red, green, blue (colorimetry.h srgb_dominant_wavelengths).
struct ConductorRgb {
    std::array<double, 3> n{}, k{};
    // the f0 reduction: a channel whose target lies outside (0, 1) (gold's red: out of the sRGB gamut) is set to the
    // nearest reachable F0 (kF0Reachable), and named here with its target
    std::string clipped;
};
ConductorRgb conductor_rgb(const MeasuredConductor& m);
constexpr const char* kConductorRgbReduction =
    "n and k at the dominant wavelengths of the sRGB primaries against D65 (611, 549, 464 nm)";

// The RGB reductions a colour study can compare (gonio compare --rgb-vs-spectral --reduction NAME):
//   dominant  conductor_rgb: n and k at the sRGB primaries' dominant wavelengths (what every RGB run uses);
//   f0        the normal-incidence reflectance matched: per channel, the linear sRGB of the spectral
//             F0(lambda) = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) under D65 (1 nm steps), reached by keeping n at the
//             dominant wavelength and solving for k (or, where even k = 0 reflects too much, k = 0 and n solved):
//             what an engine's F0 colour picked from a measured spectrum gives. A target channel outside
//             (0, 1) (gold's red is 1.04: outside sRGB's gamut) takes the nearest of [1e-4, 0.999] and says so
//             (ConductorRgb::clipped).
enum class RgbReduction { Dominant, F0 };
const char* to_string(RgbReduction r);
constexpr double kF0Reachable[2] = {1e-4, 0.999};
// Throws std::invalid_argument naming the known reductions.
RgbReduction parse_rgb_reduction(std::string_view name);
ConductorRgb conductor_rgb(const MeasuredConductor& m, RgbReduction r);
// The linear sRGB of a conductor's normal-incidence reflectance spectrum under D65 (a perfect reflector: 1, 1, 1).
std::array<double, 3> conductor_f0_srgb(const MeasuredConductor& m);

}   // namespace gonio
