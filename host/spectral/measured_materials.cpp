// measured_materials.cpp: see measured_materials.h.
#include "measured_materials.h"
#include "colorimetry.h"
#include "spectral_bands.h"
#include "spectral_table.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace gonio {

const std::vector<MeasuredConductor>& measured_conductors() {
    static const std::vector<MeasuredConductor> all = {
        {"Au", "au-johnson-christy-1972.csv", "Johnson & Christy 1972, Phys. Rev. B 6, 4370"},
        {"Ag", "ag-johnson-christy-1972.csv", "Johnson & Christy 1972, Phys. Rev. B 6, 4370"},
        {"Cu", "cu-johnson-christy-1972.csv", "Johnson & Christy 1972, Phys. Rev. B 6, 4370"},
        {"Al", "al-rakic-1995.csv", "Rakic 1995, Appl. Opt. 34, 4755"},
    };
    return all;
}

const MeasuredConductor* find_measured_conductor(std::string_view name) {
    for (const MeasuredConductor& m : measured_conductors())
        if (name == m.name) return &m;
    return nullptr;
}

std::string measured_conductor_names() {
    std::string s;
    for (const MeasuredConductor& m : measured_conductors()) s += (s.empty() ? "" : ", ") + std::string(m.name);
    return s;
}

double measured_n(const MeasuredConductor& m, double nm) {
    const SpectralTable& t = embedded_spectral_table(m.file);
    return t.at(t.column("n"), nm);
}

double measured_k(const MeasuredConductor& m, double nm) {
    const SpectralTable& t = embedded_spectral_table(m.file);
    return t.at(t.column("k"), nm);
}

ConductorRgb conductor_rgb(const MeasuredConductor& m) {
    ConductorRgb c;
    for (int i = 0; i < 3; ++i) {
        c.n[i] = measured_n(m, srgb_dominant_wavelengths()[i]);
        c.k[i] = measured_k(m, srgb_dominant_wavelengths()[i]);
    }
    return c;
}

const char* to_string(RgbReduction r) { return r == RgbReduction::F0 ? "f0" : "dominant"; }

RgbReduction parse_rgb_reduction(std::string_view name) {
    if (name == "dominant") return RgbReduction::Dominant;
    if (name == "f0") return RgbReduction::F0;
    throw std::invalid_argument("unknown RGB reduction '" + std::string(name) + "'; known: dominant, f0");
}

namespace {
double fresnel_f0(double n, double k) { return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k); }
}   // namespace

std::array<double, 3> conductor_f0_srgb(const MeasuredConductor& m) {
    SpectralBands fine;
    fine.width_nm = 1;
    const std::vector<std::array<double, 3>> w = xyz_weights(fine);
    std::array<double, 3> xyz{};
    for (size_t b = 0; b < w.size(); ++b) {
        const double nm = fine.centre_nm(b), f0 = fresnel_f0(measured_n(m, nm), measured_k(m, nm));
        for (size_t c = 0; c < 3; ++c) xyz[c] += w[b][c] * f0;
    }
    return xyz_to_linear_srgb(xyz);
}

ConductorRgb conductor_rgb(const MeasuredConductor& m, RgbReduction r) {
    ConductorRgb c = conductor_rgb(m);
    if (r == RgbReduction::Dominant) return c;
    const std::array<double, 3> target = conductor_f0_srgb(m);
    for (size_t i = 0; i < 3; ++i) {
        double f = target[i];
        if (!(f >= kF0Reachable[0] && f <= kF0Reachable[1])) {
            f = std::fmin(std::fmax(f, kF0Reachable[0]), kF0Reachable[1]);
            char line[96];
            std::snprintf(line, sizeof line, "%s%s %s F0 %.4f taken as %.4g", c.clipped.empty() ? "" : "; ", m.name,
                          i == 0 ? "red" : (i == 1 ? "green" : "blue"), target[i], f);
            c.clipped += line;
        }
        const double n = c.n[i];
        // F0 (n+1)^2 + F0 k^2 = (n-1)^2 + k^2  =>  k^2 = (F0 (n+1)^2 - (n-1)^2) / (1 - F0)
        const double k2 = (f * (n + 1) * (n + 1) - (n - 1) * (n - 1)) / (1 - f);
        if (k2 >= 0) {
            c.k[i] = std::sqrt(k2);
        } else {   // k = 0 still reflects more than F0: a dielectric's n with F0 = ((n-1)/(n+1))^2, n > 1
            c.k[i] = 0;
            c.n[i] = (1 + std::sqrt(f)) / (1 - std::sqrt(f));
        }
    }
    return c;
}

}   // namespace gonio
