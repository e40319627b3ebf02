// measured_materials.cpp: see measured_materials.h.
#include "measured_materials.h"
#include "colorimetry.h"
#include "spectral_table.h"

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

}   // namespace gonio
