// glasses.cpp: see glasses.h.
#include "glasses.h"

#include <cmath>

namespace gonio {

double Sellmeier::n(double nm) const {
    const double l2 = (nm * 1e-3) * (nm * 1e-3);
    double n2 = 1;
    for (size_t i = 0; i < 3; ++i) n2 += b[i] * l2 / (l2 - c[i]);
    return std::sqrt(n2);
}

double Cauchy::n(double nm) const {
    const double l2 = (nm * 1e-3) * (nm * 1e-3);
    return a + b / l2 + c / (l2 * l2);
}

const std::vector<NamedGlass>& named_glasses() {
    // refractiveindex.info (CC0; data/spectra/README.md): database/data/glass/schott/N-BK7.yml at commit 2d60dc27
    // (SCHOTT Zemax catalog 2017-01-20b, its "formula 2": B1 C1 B2 C2 B3 C3, C in square micrometres; relative to
    // air), database/data/main/SiO2/nk/Malitson.yml at commit 37773dce (I. H. Malitson, J. Opt. Soc. Am. 55, 1205,
    // 1965: fused silica, 20 C; its "formula 1" gives the C unsquared)
    static const std::vector<NamedGlass> all = {
        {"N-BK7",
         {{1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653}},
         "SCHOTT N-BK7 data sheet (Sellmeier), via refractiveindex.info"},
        {"fused-silica",
         {{0.6961663, 0.4079426, 0.8974794}, {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161}},
         "Malitson 1965, J. Opt. Soc. Am. 55, 1205 (Sellmeier), via refractiveindex.info"},
    };
    return all;
}

const NamedGlass* find_named_glass(std::string_view name) {
    for (const NamedGlass& g : named_glasses())
        if (name == g.name) return &g;
    return nullptr;
}

std::string named_glass_names() {
    std::string s;
    for (const NamedGlass& g : named_glasses()) s += (s.empty() ? "" : ", ") + std::string(g.name);
    return s;
}

}   // namespace gonio
