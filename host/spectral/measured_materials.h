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
};
ConductorRgb conductor_rgb(const MeasuredConductor& m);
constexpr const char* kConductorRgbReduction =
    "n and k at the dominant wavelengths of the sRGB primaries against D65 (611, 549, 464 nm)";

}   // namespace gonio
