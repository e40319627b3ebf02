// The spectral tables (data/spectra/, embedded in the binary), the colorimetry gonio takes from them, and the
// measured conductors a stack can name: the tables are the standard's (CMF integrals, D65's white point), the sRGB
// primaries' dominant wavelengths come out where colorimetry puts them, and a material's RGB reduction is its
// measured n and k at those wavelengths, read here from the files in the source tree independently.
#include "colorimetry.h"
#include "measured_materials.h"
#include "spectral_bands.h"
#include "spectral_table.h"
#include "stack.h"
#include "stack_spectral.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
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
    EXPECT_EQ(spectral_refusal(gold), "");
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
    const std::string why = spectral_refusal(tinted);
    EXPECT_NE(why.find("layer 1's optical_depth is given per RGB channel ([0.1, 0.2, 0.3])"), std::string::npos) << why;
}
