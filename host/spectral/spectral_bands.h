// spectral_bands.h: the wavelength bands of a spectral run (--spectral, --bands W: 380 to 780 nm in bands W nm wide,
// each evaluated at its centre) and how they turn into colour: CIE 1931 XYZ under D65, normalised so that a perfect
// white reflector has Y = 1, and linear sRGB (IEC 61966-2-1).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace gonio {

struct SpectralBands {
    double first_nm = 380.0, last_nm = 780.0, width_nm = 10.0;
    // How a run shares its paths between its passes (three bands each): by a pilot's measured noise (--band-paths
    // measured: minimax_pass_shares, the default), by the passes' weight in X + Y + Z (weight: pass_shares; the
    // default with an --rse target), or evenly (even: every band as many paths). chosen: given by the user.
    enum class PassPaths { Even, Weight, Measured };
    PassPaths pass_paths = PassPaths::Measured;
    bool pass_paths_chosen = false;
    // Wavelengths per band (--band-points K): a band's value is the mean of the stack's at K points spaced evenly in
    // it, the midpoints of its K equal parts (K = 1: its centre), each traced with 1/K of the band's paths: the
    // midpoint rule for the band's average, exact where the stack is linear in wavelength across each part.
    unsigned points = 1;
    static constexpr unsigned kMaxPoints = 16;

    size_t count() const;   // (last - first) / width bands; width must divide the range (checked: check())
    double centre_nm(size_t b) const { return first_nm + (double(b) + 0.5) * width_nm; }
    // point j of band b (j < points)
    double point_nm(size_t b, unsigned j) const {
        return first_nm + double(b) * width_nm + (double(j) + 0.5) * width_nm / double(points);
    }
    // Throws std::invalid_argument where the width does not divide 380-780 nm into at least 3 bands, or points is not
    // in [1, kMaxPoints].
    void check() const;
};

// Per band, its weight in X, Y and Z: the integral over the band of xbar, ybar, zbar times D65 (1 nm steps,
// trapezoids), divided by the integral of ybar times D65 over all the bands: a spectrum of ones has Y = 1.
std::vector<std::array<double, 3>> xyz_weights(const SpectralBands& bands);

// Per pass of three bands (band b in pass b / 3), the share of the run's paths it traces, as a multiple of --paths
// (their mean is 1): evenly, 1 each; by weight, proportional to the pass's summed X + Y + Z weights (xyz_weights),
// which minimises the variance of a colour that weighs the bands so for the same paths in all (Neyman allocation),
// with a floor of a quarter of the mean so that no band is left to a handful of paths.
std::vector<double> pass_shares(const SpectralBands& bands);
constexpr double kPassShareFloor = 0.25;

// The sharing a run with this --rse target (0: none) uses: the one chosen, else measured, or weight where the run has
// an --rse target (a pilot shares a fixed number of paths; with --rse each pass runs to its own error).
SpectralBands::PassPaths pass_paths_for(const SpectralBands& bands, double rse_target);

// "even", "weight", "measured"; and back (std::invalid_argument for another name).
const char* to_string(SpectralBands::PassPaths p);
SpectralBands::PassPaths parse_pass_paths(const std::string& name);

// Per pass, the share of the paths (mean 1, at least `floor`) that makes the largest of X's, Y's and Z's relative
// variances least: a[g][c] is pass g's relative variance in channel c for one path (a pilot's), and channel c's
// relative variance is sum_g a[g][c] / (q_g N). For a fixed mix lambda of the channels the least sum_c lambda_c of
// them is q_g ~ sqrt(sum_c lambda_c a[g][c]) (Neyman); the minimax is that at the mix that maximises it, found by
// raising lambda where the channel's variance is largest (multiplicative weights). A channel no pass varies in is
// left out; with none, every share is 1.
std::vector<double> minimax_pass_shares(const std::vector<std::array<double, 3>>& a, double floor);
constexpr double kMeasuredShareFloor = 0.05;

// Linear sRGB from XYZ (IEC 61966-2-1's matrix): D65's white (0.9505, 1, 1.089) gives (1, 1, 1).
std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz);

}   // namespace gonio
