// The spectral tables (data/spectra/, embedded in the binary), the colorimetry gonio takes from them, and the
// measured conductors a stack can name: the tables are the standard's (CMF integrals, D65's white point), the sRGB
// primaries' dominant wavelengths come out where colorimetry puts them, and a material's RGB reduction is its
// measured n and k at those wavelengths, read here from the files in the source tree independently.
#include "colorimetry.h"
#include "colour_difference.h"
#include "glasses.h"
#include "measured_materials.h"
#include "rgb_uplift.h"
#include "spectral_bands.h"
#include "spectral_table.h"
#include "stack.h"
#include "stack_spectral.h"

#include <gtest/gtest.h>

#include <tuple>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>

using namespace gonio;

namespace {

const std::filesystem::path kSpectra = std::filesystem::path(GONIO_SOURCE_DIR) / "data" / "spectra";

// rows (wavelength, n, k) of a data/spectra file, read with a stream, not with the parser under test
std::vector<std::array<double, 3>> read_rows(const std::string& file) {
    std::ifstream in(kSpectra / file);
    std::vector<std::array<double, 3>> rows;
    std::string line;
    bool header = false;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (!header) {
            header = true;
            continue;
        }
        std::istringstream s(line);
        std::array<double, 3> r{};
        char comma;
        s >> r[0] >> comma >> r[1] >> comma >> r[2];
        rows.push_back(r);
    }
    return rows;
}

double interpolate(const std::vector<std::array<double, 3>>& rows, double nm, int column) {
    for (size_t i = 1; i < rows.size(); ++i)
        if (rows[i][0] >= nm) {
            const double t = (nm - rows[i - 1][0]) / (rows[i][0] - rows[i - 1][0]);
            return rows[i - 1][column] + t * (rows[i][column] - rows[i - 1][column]);
        }
    return NAN;
}

}   // namespace

TEST(SpectralTable, ReadsRowsAndInterpolatesLinearly) {
    const SpectralTable t =
        parse_spectral_table("# a comment\nwavelength_nm,a,b\n400,1,10\n500,3,30\n\n600,4,0\n", "t.csv");
    EXPECT_EQ(t.columns, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(t.at(0, 400), 1.0);
    EXPECT_EQ(t.at(1, 500), 30.0);
    EXPECT_DOUBLE_EQ(t.at(0, 450), 2.0);
    EXPECT_DOUBLE_EQ(t.at(1, 575), 7.5);
    EXPECT_THROW(t.at(0, 399.9), std::out_of_range);   // nothing extrapolated
    EXPECT_THROW(t.at(0, 600.1), std::out_of_range);
    EXPECT_EQ(t.column("b"), 1u);
    EXPECT_THROW(t.column("c"), std::invalid_argument);
}

TEST(SpectralTable, RefusesMalformedFilesWithTheirLine) {
    auto message = [](const std::string& text) {
        try {
            parse_spectral_table(text, "bad.csv");
        } catch (const std::runtime_error& e) { return std::string(e.what()); }
        return std::string("accepted");
    };
    EXPECT_EQ(message("nm,a\n400,1\n500,2\n").rfind("bad.csv:1: expected the header row", 0), 0u);
    EXPECT_EQ(message("wavelength_nm,a\n400,1\n500,x\n").rfind("bad.csv:3: 'x' is not a number", 0), 0u);
    EXPECT_EQ(message("wavelength_nm,a\n400,1\n400,2\n").rfind("bad.csv:3: wavelengths must increase", 0), 0u);
    EXPECT_EQ(message("wavelength_nm,a\n400,1,2\n").rfind("bad.csv:2: expected 2 numbers, got 3", 0), 0u);
    EXPECT_EQ(message("wavelength_nm,a\n400,1\n").rfind("bad.csv:2: a table needs at least two rows", 0), 0u);
    EXPECT_EQ(message("# only\n").rfind("bad.csv:1: no header row", 0), 0u);
}

// The tables are the standard's: each colour-matching function integrates to 106.86 (CIE 015:2018, 1 nm), ybar
// peaks at 1 at 555 nm, and D65 weighted by them has the white point (0.3127, 0.3290) of IEC 61966-2-1.
TEST(Colorimetry, TheTablesAreTheStandards) {
    const SpectralTable& cmf = embedded_spectral_table("cie1931-2deg-cmf.csv");
    const SpectralTable& d65 = embedded_spectral_table("cie-d65.csv");
    double sum[3] = {0, 0, 0}, white[3] = {0, 0, 0};
    for (size_t i = 0; i < cmf.wavelength_nm.size(); ++i) {
        const double nm = cmf.wavelength_nm[i];
        for (int c = 0; c < 3; ++c) {
            sum[c] += cmf.values[c][i];   // 1 nm steps
            white[c] += cmf.values[c][i] * d65.at(0, nm);
        }
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 106.86, 0.05) << "channel " << c;
    EXPECT_EQ(cmf.at(1, 555), 1.0);
    const double s = white[0] + white[1] + white[2];
    EXPECT_NEAR(white[0] / s, 0.3127, 2e-4);
    EXPECT_NEAR(white[1] / s, 0.3290, 2e-4);
    EXPECT_EQ(d65.at(0, 560), 100.0);
}

// The dominant wavelengths of the sRGB primaries against D65: 611.3, 549.1 and 464.3 nm in the colorimetry
// literature (e.g. Hunt & Pointer, Measuring Colour, 4th ed., for the ITU-R BT.709 primaries sRGB shares); a purple
// has none; the locus at 520 nm is its green corner, x < 0.08, y > 0.8.
TEST(Colorimetry, DominantWavelengthsOfTheSrgbPrimaries) {
    const std::array<double, 3>& nm = srgb_dominant_wavelengths();
    std::printf("sRGB primaries' dominant wavelengths: %.2f, %.2f, %.2f nm\n", nm[0], nm[1], nm[2]);
    EXPECT_NEAR(nm[0], 611.3, 1.0);
    EXPECT_NEAR(nm[1], 549.1, 1.0);
    EXPECT_NEAR(nm[2], 464.3, 1.0);
    EXPECT_THROW(dominant_wavelength({0.35, 0.15}), std::invalid_argument);   // magenta
    const Chromaticity g = spectral_locus(520);
    EXPECT_LT(g.x, 0.08);
    EXPECT_GT(g.y, 0.8);
}

// Each measured conductor: its RGB reduction is n and k at the dominant wavelengths, from the file itself; gold and
// copper reflect red best, blue least, silver and aluminium above 0.9 in every channel (normal incidence, in air)
TEST(MeasuredMaterials, RgbReductionIsTheMeasuredValuesAtTheDominantWavelengths) {
    ASSERT_EQ(measured_conductor_names(), "Au, Ag, Cu, Al");
    for (const MeasuredConductor& m : measured_conductors()) {
        const auto rows = read_rows(m.file);
        ASSERT_GT(rows.size(), 10u) << m.file;
        EXPECT_LE(rows.front()[0], 380.0) << m.file;
        EXPECT_GE(rows.back()[0], 780.0) << m.file;
        const ConductorRgb rgb = conductor_rgb(m);
        double r[3];
        for (int c = 0; c < 3; ++c) {
            const double nm = srgb_dominant_wavelengths()[c];
            EXPECT_NEAR(rgb.n[c], interpolate(rows, nm, 1), 1e-12) << m.name << " channel " << c;
            EXPECT_NEAR(rgb.k[c], interpolate(rows, nm, 2), 1e-12) << m.name << " channel " << c;
            const double n = rgb.n[c], k = rgb.k[c];
            r[c] = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
        }
        std::printf("%s: n %.4f %.4f %.4f, k %.4f %.4f %.4f, R(0) %.3f %.3f %.3f\n", m.name, rgb.n[0], rgb.n[1],
                    rgb.n[2], rgb.k[0], rgb.k[1], rgb.k[2], r[0], r[1], r[2]);
        const std::string name = m.name;
        if (name == "Au" || name == "Cu") {
            EXPECT_GT(r[0], r[1]) << name;
            EXPECT_GT(r[1], r[2]) << name;
            EXPECT_LT(r[2], 0.6) << name;
        } else {
            for (double x : r) EXPECT_GT(x, 0.9) << name;
        }
    }
    EXPECT_EQ(find_measured_conductor("Zz"), nullptr);
    EXPECT_THROW(measured_n(*find_measured_conductor("Au"), 200.0), std::out_of_range);
}

// A stack that names a material: its conductor's ior and k are the reduction; written back, it names the material
// again, unless n or k was changed since (then the numbers)
TEST(MeasuredMaterials, AStackNamesOne) {
    const std::string text =
        "name = \"gold\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n"
        "[[layer]]\ninterface = \"conductor\"\nmaterial = \"Au\"\nroughness = 0.1\n";
    Stack s = parse_stack_string(text, "gold.toml");
    const ConductorRgb au = conductor_rgb(*find_measured_conductor("Au"));
    EXPECT_EQ(s.base().material, "Au");
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(s.base().ior[c], float(au.n[c]));
        EXPECT_EQ(s.base().k[c], float(au.k[c]));
    }
    EXPECT_EQ(s.base().roughness, 0.1f);
    const std::string toml = stack_to_toml(s);
    EXPECT_NE(toml.find("material = \"Au\""), std::string::npos) << toml;
    EXPECT_EQ(toml.find("\nk = "), std::string::npos) << toml;
    const Stack again = parse_stack_string(toml, "again.toml");
    EXPECT_EQ(again.base().ior, s.base().ior);
    EXPECT_EQ(again.base().k, s.base().k);
    s.layers[1].k.y = 3.0f;   // a sweep's value
    const std::string changed = stack_to_toml(s);
    EXPECT_EQ(changed.find("material"), std::string::npos) << changed;
    EXPECT_EQ(parse_stack_string(changed, "changed.toml").base().k.y, 3.0f);
}

// The bands' colour: a spectrum of ones has Y = 1 and D65's white (0.9505, 1, 1.089: IEC 61966-2-1, the bands'
// 380-780 nm leave out 0.01% of D65's Y), which linear sRGB makes (1, 1, 1); a width that does not divide the range
// is refused
TEST(SpectralBands, AWhiteSpectrumIsD65sWhite) {
    for (double width : {5.0, 10.0, 40.0}) {
        SpectralBands bands;
        bands.width_nm = width;
        ASSERT_NO_THROW(bands.check());
        const auto w = xyz_weights(bands);
        ASSERT_EQ(w.size(), size_t(400 / width));
        double xyz[3] = {0, 0, 0};
        for (const auto& b : w)
            for (int c = 0; c < 3; ++c) xyz[c] += b[size_t(c)];
        EXPECT_NEAR(xyz[1], 1.0, 1e-12) << width;
        EXPECT_NEAR(xyz[0], 0.9505, 2e-3) << width;
        EXPECT_NEAR(xyz[2], 1.0890, 3e-3) << width;
        const auto rgb = xyz_to_linear_srgb({xyz[0], xyz[1], xyz[2]});
        for (double v : rgb) EXPECT_NEAR(v, 1.0, 5e-3) << width;
        EXPECT_EQ(bands.centre_nm(0), 380 + width / 2);
    }
    SpectralBands bad;
    bad.width_nm = 7;
    EXPECT_THROW(bad.check(), std::invalid_argument);
    bad.width_nm = 200;   // two bands
    EXPECT_THROW(bad.check(), std::invalid_argument);
}

// Which stacks a spectral run takes: one value per key, or a measured material; seen at three wavelengths, each
// channel takes the material's n and k there
TEST(SpectralBands, AStackAtThreeWavelengths) {
    const Stack gold = parse_stack_string(
        "name = \"g\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n"
        "optical_depth = 0.2\n[[layer]]\ninterface = \"conductor\"\nmaterial = "
        "\"Au\"\n",
        "g.toml");
    EXPECT_EQ(spectral_refusal(gold, 385, 775), "");
    const Stack at = stack_at_wavelengths(gold, {400.0, 550.0, 700.0});
    const MeasuredConductor& au = *find_measured_conductor("Au");
    for (int c = 0; c < 3; ++c) {
        const double nm = std::array<double, 3>{400.0, 550.0, 700.0}[size_t(c)];
        EXPECT_EQ(at.base().ior[c], float(measured_n(au, nm)));
        EXPECT_EQ(at.base().k[c], float(measured_k(au, nm)));
        EXPECT_EQ(at.layers[0].optical_depth[c], 0.2f);
    }
    const Stack tinted = parse_stack_string(
        "name = \"t\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n"
        "optical_depth = [0.1, 0.2, 0.3]\n[[layer]]\ninterface = \"lambertian\"\n"
        "albedo = 0.5\n",
        "t.toml");
    // an RGB optical depth is uplifted (RgbUplift tests below); an RGB conductor's k is not
    EXPECT_EQ(spectral_refusal(tinted, 385, 775), "");
    const Stack rgb_k = parse_stack_string(
        "name = \"k\"\n[[layer]]\ninterface = \"conductor\"\nior = 0.2\nk = [3, 2.5, 2]\n", "k.toml");
    const std::string why = spectral_refusal(rgb_k, 385, 775);
    EXPECT_NE(why.find("layer 1's k is given per RGB channel ([3, 2.5, 2])"), std::string::npos) << why;
    EXPECT_NE(why.find("it is not uplifted from RGB"), std::string::npos) << why;
    EXPECT_NE(why.find("material = \"Au\""), std::string::npos) << why;
    // a material whose n or k a sweep or a fit changed no longer describes the layer: refused, not traced as measured
    Stack changed = gold;
    changed.layers[1].k.x += 0.5f;
    EXPECT_NE(spectral_refusal(changed, 385, 775).find("ior or k was changed from material Au"), std::string::npos);
    changed.layers[1].k = glm::vec3(3.0f);
    EXPECT_NE(spectral_refusal(changed, 385, 775).find("ior or k was changed from material Au"), std::string::npos)
        << spectral_refusal(changed, 385, 775);
    // Johnson & Christy's gold is measured from 292 nm: a range below it is refused with both ranges
    EXPECT_NE(spectral_refusal(gold, 250, 775).find("material Au is measured from 292"), std::string::npos)
        << spectral_refusal(gold, 250, 775);
}

// A key given as a spectrum (pairs [nm, value]): its RGB the values at the dominant wavelengths (as a material's),
// its value at each wavelength in a spectral run, written back as pairs; what is not a spectrum refused at its line.
TEST(KeySpectrum, AnOpticalDepthSpectrum) {
    const Stack s = parse_stack_string(
        "name = \"s\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n"
        "optical_depth = [[380, 0.9], [500, 0.3], [780, 0.1]]\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n",
        "s.toml");
    auto tau = [](double nm) {
        return nm <= 500 ? 0.9 + (nm - 380) / 120 * (0.3 - 0.9) : 0.3 + (nm - 500) / 280 * (0.1 - 0.3);
    };
    for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(s.layers[0].optical_depth[c], float(tau(srgb_dominant_wavelengths()[size_t(c)])));
    EXPECT_EQ(spectral_refusal(s, 385, 775), "");
    const Stack at = stack_at_wavelengths(s, {400.0, 550.0, 700.0});
    for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(at.layers[0].optical_depth[c],
                        float(tau(std::array<double, 3>{400.0, 550.0, 700.0}[size_t(c)])));
    const Stack again = parse_stack_string(stack_to_toml(s), "again.toml");
    EXPECT_EQ(again.layers[0].optical_depth, s.layers[0].optical_depth);
    ASSERT_EQ(again.layers[0].spectra.size(), 1u);
    EXPECT_EQ(again.layers[0].spectra[0].table.wavelength_nm, s.layers[0].spectra[0].table.wavelength_nm);
    // a sweep's value replaces the spectrum: written as the value, and refused by a spectral run where it is RGB
    Stack swept = s;
    swept.layers[0].optical_depth = glm::vec3(0.4f);
    EXPECT_EQ(stack_to_toml(swept).find("[[380"), std::string::npos);
    EXPECT_EQ(stack_at_wavelengths(swept, {400.0, 550.0, 700.0}).layers[0].optical_depth, glm::vec3(0.4f));
    EXPECT_NE(spectral_refusal(s, 350, 775).find("optical_depth spectrum covers 380 to 780 nm"), std::string::npos);
    struct Bad {
        const char* value;
        const char* says;
    };
    const Bad bad[] = {
        {"[[380, 0.9], [380, 0.3]]", "wavelengths must increase, got 380 nm after 380 nm"},
        {"[[380, 0.9], [500]]", "expected a pair [nm, value]"},
        {"[[380, 0.9]]", "a spectrum needs at least 2 pairs"},
        {"[[380, 0.9], [500, -1]]", "must be in"},
        {"[[500, 0.9], [780, 0.3]]", "it must cover at least 464.30"},
        {"[[380, 0.9], [\"x\", 0.3]]", "wavelength"},
    };
    for (const Bad& b : bad) {
        try {
            parse_stack_string(
                std::string("name = \"b\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\noptical_depth = ") +
                    b.value + "\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n",
                "b.toml");
            ADD_FAILURE() << b.value << " was accepted";
        } catch (const StackError& e) {
            EXPECT_NE(std::string(e.what()).find(b.says), std::string::npos) << e.what();
            EXPECT_EQ(e.line, 5) << e.what();
        }
    }
    // a dielectric's ior as a spectrum disperses: one value in every channel in RGB, the d line's; a spectral pass
    // takes one wavelength in every channel, never three
    const Stack d = parse_stack_string(
        "name = \"d\"\n[[layer]]\ninterface = \"dielectric\"\nior = [[380, 1.55], [780, 1.5]]\n"
        "[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n",
        "d.toml");
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(d.layers[0].ior[c], float(1.55 + (587.56 - 380) / 400 * (1.5 - 1.55)));
    EXPECT_TRUE(stack_disperses(d));
    EXPECT_FALSE(stack_disperses(s));
    EXPECT_FLOAT_EQ(stack_at_wavelengths(d, {480.0, 480.0, 480.0}).layers[0].ior.y, float(1.55 - 0.05 * 100 / 400));
    EXPECT_THROW(stack_at_wavelengths(d, {400.0, 550.0, 700.0}), std::logic_error);
}

// CIEDE2000 against Sharma, Wu and Dalal (2005), Table 1: published pairs (Lab) and their differences, covering the
// hue's wrap-around, the mean hue's cases and the rotation term.
TEST(ColourDifference, Ciede2000IsSharmasTestData) {
    struct Pair {
        gonio::Colour3 a, b;
        double de;
    };
    const Pair pairs[] = {{{50, 2.6772, -79.7751}, {50, 0, -82.7485}, 2.0425},
                          {{50, 3.1571, -77.2803}, {50, 0, -82.7485}, 2.8615},
                          {{50, 2.8361, -74.0200}, {50, 0, -82.7485}, 3.4412},
                          {{50, 0, 0}, {50, -1, 2}, 2.3669},
                          {{50, 2.5, 0}, {73, 25, -18}, 27.1492},
                          {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644}};
    for (const Pair& p : pairs) {
        EXPECT_NEAR(gonio::delta_e_2000(p.a, p.b), p.de, 5e-5);
        EXPECT_NEAR(gonio::delta_e_2000(p.b, p.a), p.de, 5e-5);   // symmetric
    }
    EXPECT_EQ(gonio::delta_e_2000({40, 10, -5}, {40, 10, -5}), 0.0);
}

// ICtCp: D65's white is achromatic (Ct = Cp = 0) with I the PQ of its luminance (100 cd/m^2: 0.5081, SMPTE ST 2084);
// the differences of XYZ reflectance factors against colour-science 0.4.7 (colour.delta_E, 'CIE 2000' on XYZ_to_Lab
// with D65, 'ITP' on XYZ_to_ICtCp of XYZ x 100 cd/m^2), an independent implementation.
TEST(ColourDifference, ItpAndCielabAgreeWithColourScience) {
    const gonio::Colour3 white = gonio::linear_srgb_to_xyz({1, 1, 1});
    const gonio::Colour3 i = gonio::xyz_to_ictcp({white[0] * 100, white[1] * 100, white[2] * 100});
    EXPECT_NEAR(i[0], 0.508078677, 1e-4);
    EXPECT_NEAR(i[1], 0, 1e-4);
    EXPECT_NEAR(i[2], 0, 1e-4);
    const gonio::Colour3 lab = gonio::xyz_to_lab({0.3, 0.25, 0.2});
    EXPECT_NEAR(lab[0], 57.07542089, 1e-6);
    EXPECT_NEAR(lab[1], 25.45386855, 1e-6);
    EXPECT_NEAR(lab[2], 12.31063236, 1e-6);
    struct Case {
        gonio::Colour3 a, b;
        double de2000, de_itp;
    };
    const Case cases[] = {{{0.30, 0.25, 0.20}, {0.31, 0.25, 0.19}, 1.809202, 7.521554},
                          {{0.9505, 1.0, 1.089}, {0.8, 0.85, 1.0}, 6.053297, 13.087096},
                          {{12.0, 10.0, 3.0}, {11.0, 10.5, 4.0}, 16.993802, 33.330902},
                          {{0.02, 0.015, 0.01}, {0.018, 0.016, 0.012}, 6.364601, 21.475363}};
    for (const Case& c : cases) {
        const gonio::ColourDifference d = gonio::colour_difference(c.a, c.b);
        EXPECT_NEAR(d.de2000, c.de2000, 1e-4 * c.de2000);
        EXPECT_NEAR(d.de_itp, c.de_itp, 1e-5 * c.de_itp);
    }
}

// The f0 reduction reaches, per channel, the linear sRGB of the spectral normal-incidence reflectance, keeping n at
// the dominant wavelength; gold's F0 is yellow (red > green > blue) and the dominant reduction's differs from it.
TEST(MeasuredMaterials, TheF0ReductionMatchesTheSpectralF0) {
    for (const gonio::MeasuredConductor& m : gonio::measured_conductors()) {
        const std::array<double, 3> target = gonio::conductor_f0_srgb(m);
        const gonio::ConductorRgb dominant = gonio::conductor_rgb(m, gonio::RgbReduction::Dominant);
        const gonio::ConductorRgb f0 = gonio::conductor_rgb(m, gonio::RgbReduction::F0);
        for (size_t c = 0; c < 3; ++c) {
            const double n = f0.n[c], k = f0.k[c];
            const double reached = std::fmin(std::fmax(target[c], gonio::kF0Reachable[0]), gonio::kF0Reachable[1]);
            EXPECT_NEAR(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), reached, 1e-12) << m.name << c;
            EXPECT_EQ(reached != target[c],
                      f0.clipped.find(c == 0 ? "red" : (c == 1 ? "green" : "blue")) != std::string::npos)
                << m.name << c << f0.clipped;
            if (k > 0) EXPECT_EQ(n, dominant.n[c]) << m.name << c;
        }
    }
    const std::array<double, 3> au = gonio::conductor_f0_srgb(*gonio::find_measured_conductor("Au"));
    EXPECT_GT(au[0], au[1]);
    EXPECT_GT(au[1], au[2]);
    // a flat F0 spectrum of one is D65's white: (1, 1, 1) in linear sRGB, to the matrix's 4 digits
    gonio::SpectralBands fine;
    fine.width_nm = 1;
    std::array<double, 3> xyz{};
    for (const auto& w : gonio::xyz_weights(fine))
        for (size_t c = 0; c < 3; ++c) xyz[c] += w[c];
    for (double v : gonio::xyz_to_linear_srgb(xyz)) EXPECT_NEAR(v, 1.0, 2e-3);
    EXPECT_THROW(gonio::parse_rgb_reduction("cmf"), std::invalid_argument);
}

// The default sharing is the pilot's (measured), and by weight where the run has an --rse target unless one is chosen.
TEST(SpectralBands, TheDefaultSharingIsMeasuredAndWeightWithAnRseTarget) {
    using P = gonio::SpectralBands::PassPaths;
    gonio::SpectralBands b;
    EXPECT_EQ(gonio::pass_paths_for(b, 0.0), P::Measured);
    EXPECT_EQ(gonio::pass_paths_for(b, 0.01), P::Weight);
    b.pass_paths = P::Even;
    b.pass_paths_chosen = true;
    EXPECT_EQ(gonio::pass_paths_for(b, 0.01), P::Even);
    b.pass_paths = P::Measured;   // chosen with an --rse target: refused where the run starts, not changed here
    EXPECT_EQ(gonio::pass_paths_for(b, 0.01), P::Measured);
}

// The passes' shares of the paths: even gives every pass --paths; by weight their mean is --paths, none below the
// floor, the pass of 440-470 nm (where zbar peaks, at 1.78 against ybar's 1) the largest, and the shares follow the
// X + Y + Z weights above the floor.
TEST(SpectralBands, PassSharesFollowTheColourWeights) {
    gonio::SpectralBands even;
    even.pass_paths = gonio::SpectralBands::PassPaths::Even;
    for (double q : gonio::pass_shares(even)) EXPECT_EQ(q, 1.0);
    gonio::SpectralBands bands;
    bands.pass_paths = gonio::SpectralBands::PassPaths::Weight;
    const std::vector<double> q = gonio::pass_shares(bands);
    ASSERT_EQ(q.size(), 14u);
    double sum = 0;
    for (double x : q) {
        sum += x;
        EXPECT_GE(x, gonio::kPassShareFloor);
    }
    EXPECT_NEAR(sum / 14, 1.0, 1e-12);
    const size_t peak = size_t(std::max_element(q.begin(), q.end()) - q.begin());
    EXPECT_EQ(peak, 2u);   // bands 6-8: 440-470 nm
    const auto w = gonio::xyz_weights(bands);
    auto weight = [&](size_t g) {
        double s = 0;
        for (size_t b = 3 * g; b < std::min<size_t>(40, 3 * g + 3); ++b) s += w[b][0] + w[b][1] + w[b][2];
        return s;
    };
    for (size_t g = 0; g < 14; ++g)
        for (size_t h = 0; h < 14; ++h)
            if (q[g] > gonio::kPassShareFloor && q[h] > gonio::kPassShareFloor)
                EXPECT_NEAR(q[g] / q[h], weight(g) / weight(h), 1e-9);
}

// --band-points K: the midpoints of a band's K equal parts; 1 is its centre; K outside [1, 16] refused
TEST(SpectralBands, PointsAreTheMidpointsOfEqualParts) {
    gonio::SpectralBands b;
    EXPECT_EQ(b.point_nm(0, 0), b.centre_nm(0));
    b.width_nm = 20;
    b.points = 4;
    b.check();
    EXPECT_DOUBLE_EQ(b.point_nm(0, 0), 382.5);
    EXPECT_DOUBLE_EQ(b.point_nm(0, 3), 397.5);
    EXPECT_DOUBLE_EQ(b.point_nm(19, 3), 777.5);
    b.points = 0;
    EXPECT_THROW(b.check(), std::invalid_argument);
    b.points = 17;
    EXPECT_THROW(b.check(), std::invalid_argument);
}

// --band-paths measured's shares: the minimax of the channels' relative variances sum_g a[g][c] / q_g. One pass
// carrying all of X with 4 times the variance of another carrying all of Z: the two variances are equal at q0 = 4 q1,
// so (1.6, 0.4); a channel no pass varies in is left out; none at all: every share 1; the floor holds.
TEST(SpectralBands, MinimaxSharesEqualiseTheChannels) {
    const std::vector<double> q = gonio::minimax_pass_shares({{4, 0, 0}, {0, 0, 1}}, 0.05);
    ASSERT_EQ(q.size(), 2u);
    EXPECT_NEAR(q[0], 1.6, 2e-3);
    EXPECT_NEAR(q[1], 0.4, 2e-3);
    for (double x : gonio::minimax_pass_shares({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, 0.05)) EXPECT_EQ(x, 1.0);
    const std::vector<double> f = gonio::minimax_pass_shares({{1, 1, 1}, {1e-8, 0, 0}, {1, 1, 1}}, 0.1);
    EXPECT_NEAR(f[1], 0.1, 1e-9);   // held at the floor, the rest sharing what is left
    EXPECT_NEAR(f[0], 1.45, 1e-6);
    EXPECT_NEAR(f[0] + f[1] + f[2], 3.0, 1e-9);
    // against a brute-force search over shares summing to 3: no split has a smaller largest variance
    const std::vector<std::array<double, 3>> a = {{0.2, 1.0, 3.0}, {1.0, 1.5, 0.5}, {2.0, 0.3, 0.1}};
    const std::vector<double> m = gonio::minimax_pass_shares(a, 0.05);
    auto worst = [&](double q0, double q1, double q2) {
        double w = 0;
        for (int c = 0; c < 3; ++c) w = std::max(w, a[0][size_t(c)] / q0 + a[1][size_t(c)] / q1 + a[2][size_t(c)] / q2);
        return w;
    };
    double best = INFINITY;
    for (double q0 = 0.05; q0 < 2.9; q0 += 0.005)
        for (double q1 = 0.05; q0 + q1 < 2.95; q1 += 0.005) best = std::min(best, worst(q0, q1, 3 - q0 - q1));
    EXPECT_LE(worst(m[0], m[1], m[2]), best * 1.001);
}

// Named glasses and dispersion formulas: N-BK7's Sellmeier gives its data sheet's n_d 1.51680, n_F 1.52238 and n_C
// 1.51432 (Abbe number 64.17); Malitson's fused silica n_d 1.45846; a stack names them (its RGB value the d line's) and
// writes them back by name; a Cauchy formula is A + B / lambda^2; unknown names and malformed formulas refused.
TEST(Glasses, NamedGlassesAndFormulas) {
    const gonio::NamedGlass& bk7 = *gonio::find_named_glass("N-BK7");
    EXPECT_NEAR(bk7.formula.n(587.56), 1.51680, 2e-5);
    EXPECT_NEAR(bk7.formula.n(486.13), 1.52238, 2e-5);
    EXPECT_NEAR(bk7.formula.n(656.27), 1.51432, 2e-5);
    EXPECT_NEAR((bk7.formula.n(587.56) - 1) / (bk7.formula.n(486.13) - bk7.formula.n(656.27)), 64.17, 0.05);
    EXPECT_NEAR(gonio::find_named_glass("fused-silica")->formula.n(587.56), 1.45846, 2e-5);
    // SCHOTT's data sheets: N-F2 n_d 1.62005, V_d 36.43; N-SF11 n_d 1.78472, V_d 25.68 (each file's SPECS)
    for (auto [name, nd, vd] : {std::tuple{"N-F2", 1.62005, 36.43}, std::tuple{"N-SF11", 1.78472, 25.68}}) {
        const gonio::Sellmeier& f = gonio::find_named_glass(name)->formula;
        EXPECT_NEAR(f.n(587.56), nd, 2e-5) << name;
        EXPECT_NEAR((f.n(587.56) - 1) / (f.n(486.13) - f.n(656.27)), vd, 0.05) << name;
    }
    // calcium fluoride: n_d 1.43385 and V_d 94.99 (Malitson 1963's formula as optical catalogues quote it)
    const gonio::Sellmeier& caf2 = gonio::find_named_glass("CaF2")->formula;
    EXPECT_NEAR(caf2.n(587.56), 1.43385, 5e-5);
    EXPECT_NEAR((caf2.n(587.56) - 1) / (caf2.n(486.13) - caf2.n(656.27)), 94.99, 0.3);
    EXPECT_EQ(gonio::find_named_glass("BK7"), nullptr);
    // a glass is tabulated only where its source's formula holds: N-SF11 from 370 nm
    const Stack sf11 = parse_stack_string(
        "name = \"f\"\n[[layer]]\ninterface = \"dielectric\"\nior = \"N-SF11\"\n"
        "[[layer]]\ninterface = \"dielectric\"\nior = 1\n",
        "f.toml");
    EXPECT_EQ(sf11.layers[0].spectra.front().table.first_nm(), 370.0);
    EXPECT_EQ(sf11.layers[0].spectra.front().table.last_nm(), 900.0);
    EXPECT_THROW(stack_at_wavelengths(sf11, {360, 360, 360}), std::out_of_range);
    const Stack s = parse_stack_string(
        "name = \"g\"\n[[layer]]\ninterface = \"dielectric\"\nior = \"N-BK7\"\n"
        "[[layer]]\ninterface = \"dielectric\"\nior = 1\n",
        "g.toml");
    EXPECT_NEAR(s.layers[0].ior.x, 1.51680, 2e-5);
    EXPECT_TRUE(stack_disperses(s));
    EXPECT_NE(stack_to_toml(s).find("ior = \"N-BK7\""), std::string::npos) << stack_to_toml(s);
    EXPECT_EQ(parse_stack_string(stack_to_toml(s), "again.toml").layers[0].ior, s.layers[0].ior);
    EXPECT_NEAR(stack_at_wavelengths(s, {486.13, 486.13, 486.13}).layers[0].ior.x, 1.52238, 1e-4);   // 2 nm table
    const Stack c = parse_stack_string(
        "name = \"c\"\n[[layer]]\ninterface = \"dielectric\"\n"
        "ior = { cauchy = [1.5, 0.005] }\n[[layer]]\ninterface = \"lambertian\"\n"
        "albedo = 0.5\n",
        "c.toml");
    EXPECT_NEAR(c.layers[0].ior.x, 1.5 + 0.005 / (0.58756 * 0.58756), 1e-5);
    for (const char* bad :
         {"\"BK7\"", "{ sellmeier = [1, 2] }", "{ cauchy = [1.5] }", "{ abbe = [1.5, 60] }", "{ cauchy = [0.5, 0] }"})
        EXPECT_THROW(parse_stack_string(std::string("name = \"b\"\n[[layer]]\ninterface = \"dielectric\"\nior = ") +
                                            bad + "\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n",
                                        "b.toml"),
                     StackError)
            << bad;
}

namespace {

// The colour of a spectrum at gonio's bands of width_nm (xyz_weights, each band at its centre), linear sRGB divided
// channel by channel by that of a spectrum of ones: computed here from the band weights, not by rgb_uplift.cpp.
std::array<double, 3> balanced_colour(const std::function<double(double)>& s, double width_nm) {
    SpectralBands bands;
    bands.width_nm = width_nm;
    const auto w = xyz_weights(bands);
    std::array<double, 3> xyz{0, 0, 0}, white{0, 0, 0};
    for (size_t b = 0; b < w.size(); ++b)
        for (size_t i = 0; i < 3; ++i) {
            xyz[i] += w[b][i] * s(bands.centre_nm(b));
            white[i] += w[b][i];
        }
    std::array<double, 3> rgb = xyz_to_linear_srgb(xyz);
    const std::array<double, 3> white_rgb = xyz_to_linear_srgb(white);
    for (size_t c = 0; c < 3; ++c) rgb[c] /= white_rgb[c];
    return rgb;
}

double cie76(const std::array<double, 3>& rgb1, const std::array<double, 3>& rgb2) {
    const Colour3 a = xyz_to_lab(linear_srgb_to_xyz(rgb1)), b = xyz_to_lab(linear_srgb_to_xyz(rgb2));
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

}   // namespace

// Jakob & Hanika 2019: the uplifted spectrum of every colour of a grid over [0.02, 0.98]^3, and of the sRGB cube's
// corners and saturated colours (channels at exactly 0 and 1), has the colour asked for at 1 nm bands within
// |delta RGB| < 1e-6 (the solver stops at CIE76 1e-9) and stays in (0, 1) from 360 to 830 nm; at gonio's 5 nm and
// 10 nm bands (a spectral run's) its colour is within 5e-4 and 2e-3 of it (the bands' midpoint rule, below)
TEST(RgbUplift, ColoursRoundTrip) {
    std::vector<std::array<double, 3>> colours;
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j)
            for (int k = 0; k < 9; ++k) colours.push_back({0.02 + 0.12 * i, 0.02 + 0.12 * j, 0.02 + 0.12 * k});
    for (int corner = 1; corner < 7; ++corner)   // the primaries and secondaries, and at 0.98 / 0.02
        for (double hi : {1.0, 0.98}) {
            std::array<double, 3> c{};
            for (size_t b = 0; b < 3; ++b) c[b] = (corner >> b) & 1 ? hi : 1 - hi;
            colours.push_back(c);
        }
    for (const auto& c : std::vector<std::array<double, 3>>{
             {0.8, 0.5, 0.2}, {1, 0.6, 0.37}, {1, 1, 0.99}, {0.001, 0, 0}, {0.5, 0.5, 0.49}})
        colours.push_back(c);
    double worst_rgb = 0, worst_de = 0, worst_5nm = 0, worst_10nm = 0;
    for (const auto& c : colours) {
        const RgbUplift u = uplift_rgb(c);
        ASSERT_TRUE(u.reached) << c[0] << " " << c[1] << " " << c[2] << ": dE " << u.delta_e76;
        const auto s = [&](double nm) { return u.spectrum.at(nm); };
        const auto rgb = balanced_colour(s, 1.0);
        for (size_t i = 0; i < 3; ++i) worst_rgb = std::max(worst_rgb, std::fabs(rgb[i] - c[i]));
        worst_de = std::max(worst_de, cie76(rgb, c));
        for (size_t i = 0; i < 3; ++i) {
            worst_5nm = std::max(worst_5nm, std::fabs(balanced_colour(s, 5.0)[i] - c[i]));
            worst_10nm = std::max(worst_10nm, std::fabs(balanced_colour(s, 10.0)[i] - c[i]));
        }
        if (c[0] == c[1] && c[1] == c[2]) continue;
        for (double nm = 360; nm <= 830; nm += 1) {
            ASSERT_GT(s(nm), 0.0) << nm;
            ASSERT_LT(s(nm), 1.0) << nm;
        }
    }
    EXPECT_LT(worst_rgb, 1e-6);
    EXPECT_LT(worst_de, 1e-3);
    // the run's bands read s at their centres: the midpoint rule, its error in h^2 (10 nm 4x 5 nm's), largest for
    // the steepest spectra (the saturated colours), 1.2e-4 for (0.8, 0.5, 0.2) at 10 nm
    EXPECT_LT(worst_5nm, 5e-4);
    EXPECT_LT(worst_10nm, 2e-3);
    EXPECT_NEAR(worst_10nm / worst_5nm, 4.0, 0.5);
    std::printf(
        "uplift round trip over %zu colours: |dRGB| %.2g, CIE76 %.2g at 1 nm bands; |dRGB| %.2g at 5 nm, "
        "%.2g at 10 nm\n",
        colours.size(), worst_rgb, worst_de, worst_5nm, worst_10nm);
}

// A grey is the constant spectrum, exactly: c0 = c1 = 0, its value at every wavelength the grey's (0 and 1 too); a
// channel outside [0, 1] is refused
TEST(RgbUplift, GreyIsConstant) {
    for (double v : {0.0, 1e-3, 0.2, 0.5, 0.8, 1.0}) {
        const RgbUplift u = uplift_rgb({v, v, v});
        EXPECT_TRUE(u.grey && u.reached);
        EXPECT_EQ(u.spectrum.c[0], 0.0);
        EXPECT_EQ(u.spectrum.c[1], 0.0);
        for (double nm = 360; nm <= 830; nm += 10) EXPECT_NEAR(u.spectrum.at(nm), v, 1e-15) << v << " " << nm;
        if (v == 0 || v == 1) { EXPECT_EQ(u.spectrum.at(500), v); }
        for (double x : balanced_colour([&](double nm) { return u.spectrum.at(nm); }, 1.0)) EXPECT_NEAR(x, v, 1e-12);
    }
    EXPECT_THROW(uplift_rgb({0.5, 1.2, 0.5}), std::invalid_argument);
    EXPECT_THROW(uplift_rgb({-0.1, 0.5, 0.5}), std::invalid_argument);
    EXPECT_THROW(uplift_rgb({NAN, 0.5, 0.5}), std::invalid_argument);
    // the coefficients per nm are the same quadratic
    const RgbUplift u = uplift_rgb({0.8, 0.5, 0.2});
    const auto a = u.spectrum.per_nm();
    for (double nm : {400.0, 555.0, 700.0})
        EXPECT_NEAR(uplift_sigmoid((a[0] * nm + a[1]) * nm + a[2]), u.spectrum.at(nm), 1e-12);
}

// A stack's RGB keys in a spectral run: an albedo takes its uplifted spectrum's value at each wavelength; an optical
// depth its transmittance's -ln s, >= 0 everywhere (also where a channel's tau is 0), whose exp(-tau) has the colour
// exp(-tau) per channel; the RGB values stay as given (the RGB run)
TEST(RgbUplift, AStacksRgbKeysInASpectralRun) {
    const Stack s = parse_stack_string(
        "name = \"u\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\noptical_depth = [0, 0.4, 1.2]\n"
        "scattering_albedo = [0.9, 0.6, 0.3]\n[[layer]]\ninterface = \"lambertian\"\nalbedo = [0.8, 0.5, 0.2]\n",
        "u.toml");
    EXPECT_EQ(s.layers[1].albedo, glm::vec3(0.8f, 0.5f, 0.2f));
    EXPECT_EQ(spectral_refusal(s, 385, 775), "");
    const std::vector<KeyUplift> ups = stack_uplifts(s);
    ASSERT_EQ(ups.size(), 3u);
    EXPECT_EQ(ups[0].key, "optical_depth");
    EXPECT_TRUE(ups[0].through_transmittance);
    EXPECT_EQ(ups[1].key, "scattering_albedo");
    EXPECT_EQ(ups[2].key, "albedo");
    EXPECT_EQ(ups[2].layer, 1u);
    for (const KeyUplift& u : ups) ASSERT_TRUE(u.uplift.reached) << u.key;
    for (double nm = 380; nm <= 780; nm += 1) ASSERT_GT(ups[0].value_at(nm), 0.0) << nm;
    const auto t = balanced_colour([&](double nm) { return std::exp(-ups[0].value_at(nm)); }, 1.0);
    const std::array<double, 3> want{1.0, std::exp(-double(0.4f)), std::exp(-double(1.2f))};
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(t[c], want[c], 1e-6) << c;
    const auto albedo = balanced_colour([&](double nm) { return ups[2].value_at(nm); }, 1.0);
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(albedo[c], double(s.layers[1].albedo[int(c)]), 1e-6) << c;
    const std::array<double, 3> nm{420.0, 530.0, 640.0};
    const Stack at = stack_at_wavelengths(s, nm);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(at.layers[0].optical_depth[c], float(ups[0].value_at(nm[size_t(c)])));
        EXPECT_EQ(at.layers[0].scattering_albedo[c], float(ups[1].value_at(nm[size_t(c)])));
        EXPECT_EQ(at.layers[1].albedo[c], float(ups[2].value_at(nm[size_t(c)])));
    }
    // a grey key is not uplifted: the same value at every wavelength
    Stack grey = s;
    grey.layers[1].albedo = glm::vec3(0.3f);
    EXPECT_EQ(stack_uplifts(grey).size(), 2u);
    EXPECT_EQ(stack_at_wavelengths(grey, nm).layers[1].albedo, glm::vec3(0.3f));
}

// The authors' own optimiser (pbrt-v4 src/pbrt/cmd/rgb2spec_opt.cpp, commit 5f7a606806a4ac7b939131ded9d7a30ebd02416e,
// its gauss_newton continued in brightness from coefficients 0 as its table is, run outside gonio) gives these
// spectra at 450, 550 and 650 nm; gonio's differ by at most 2.9e-4 (its colour: 1 nm bands over 380-780 nm, white
// balanced; theirs: the 5 nm CIE tables over 360-830 nm, Simpson's 3/8 rule)
TEST(RgbUplift, AgreesWithTheAuthorsOptimiser) {
    struct Case {
        std::array<double, 3> rgb, s;
    };
    const Case cases[] = {{{0.8, 0.5, 0.2}, {0.22576, 0.52612, 0.78664}},
                          {{0.2, 0.4, 0.8}, {0.77421, 0.37703, 0.24330}},
                          {{0.9, 0.1, 0.1}, {0.10181, 0.11784, 0.96550}},
                          {{0.3, 0.7, 0.3}, {0.30084, 0.67783, 0.15183}}};
    for (const Case& c : cases) {
        const RgbUplift u = uplift_rgb(c.rgb);
        for (size_t i = 0; i < 3; ++i)
            EXPECT_NEAR(u.spectrum.at(450.0 + 100.0 * double(i)), c.s[i], 1e-3) << c.rgb[0] << " " << c.rgb[1];
    }
}
