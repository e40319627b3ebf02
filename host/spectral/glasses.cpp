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
    // refractiveindex.info (CC0; data/spectra/README.md). SCHOTT's glasses: database/data/glass/schott/<name>.yml at
    // commit 2d60dc27 (SCHOTT Zemax catalog 2017-01-20b, its "formula 2": B1 C1 B2 C2 B3 C3, C in square
    // micrometres; relative to air, 20 C; each file's wavelength_range). The crystals and fused silica:
    // database/data/main/SiO2/nk/Malitson.yml at commit 37773dce (I. H. Malitson, J. Opt. Soc. Am. 55, 1205, 1965:
    // fused silica, 20 C) and main/CaF2/nk/Malitson.yml at commit c817541a (I. H. Malitson, Appl. Opt. 2, 1103,
    // 1963: calcium fluoride, 24 C); their "formula 1" gives the C unsquared
    static const std::vector<NamedGlass> all = {
        {"N-BK7",
         {{1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653}},
         "SCHOTT N-BK7 data sheet (Sellmeier), via refractiveindex.info",
         300,
         2500},
        {"N-F2",
         {{1.39757037, 0.159201403, 1.2686543}, {0.00995906143, 0.0546931752, 119.248346}},
         "SCHOTT N-F2 data sheet (Sellmeier), via refractiveindex.info",
         365,
         2500},
        {"N-SF11",
         {{1.73759695, 0.313747346, 1.89878101}, {0.013188707, 0.0623068142, 155.23629}},
         "SCHOTT N-SF11 data sheet (Sellmeier), via refractiveindex.info",
         370,
         2500},
        {"fused-silica",
         {{0.6961663, 0.4079426, 0.8974794}, {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161}},
         "Malitson 1965, J. Opt. Soc. Am. 55, 1205 (Sellmeier), via refractiveindex.info",
         210,
         6700},
        {"CaF2",
         {{0.5675888, 0.4710914, 3.8484723}, {0.050263605 * 0.050263605, 0.1003909 * 0.1003909, 34.649040 * 34.649040}},
         "Malitson 1963, Appl. Opt. 2, 1103 (calcium fluoride, Sellmeier), via refractiveindex.info",
         230,
         9700},
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
