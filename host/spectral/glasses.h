// glasses.h: dielectrics whose index depends on wavelength: named glasses (Sellmeier coefficients from their makers'
// data sheets, via the CC0 refractiveindex.info database) and the Sellmeier and Cauchy formulas a stack may give for
// a dielectric's `ior` (docs/SPECTRAL.md, "Dispersion").
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace gonio {

// n(lambda)^2 = 1 + sum_i B_i lambda^2 / (lambda^2 - C_i), lambda in micrometres, C_i in square micrometres.
struct Sellmeier {
    std::array<double, 3> b{}, c{};
    double n(double nm) const;
};

// n(lambda) = A + B / lambda^2 (+ C / lambda^4), lambda in micrometres.
struct Cauchy {
    double a = 1.5, b = 0, c = 0;
    double n(double nm) const;
};

struct NamedGlass {
    const char* name;   // what a stack writes: ior = "N-BK7"
    Sellmeier formula;
    const char* reference;
    double first_nm, last_nm;   // where the source says its formula holds (a stack tabulates it only there)
};

const std::vector<NamedGlass>& named_glasses();
const NamedGlass* find_named_glass(std::string_view name);   // nullptr: no such glass
std::string named_glass_names();   // "N-BK7, fused silica, ..."

}   // namespace gonio
