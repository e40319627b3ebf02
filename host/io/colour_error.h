// colour_error.h: how far a stack's RGB run is from its spectral run in colour (gonio compare --rgb-vs-spectral,
// docs/SPECTRAL.md): per bin and per incident angle, CIEDE2000 and Delta E_ITP between the two runs' colours, each
// bin taken as its reflectance factor pi f under D65 (colour_difference.h: a perfect white diffuser has Y = 1).
#pragma once

#include "colour_difference.h"
#include "histogram.h"
#include "json.h"
#include "spectral_output.h"

#include <glm/glm.hpp>
#include <array>
#include <string>
#include <vector>

namespace gonio {

// A bin counts in the summaries where the spectral run's reflectance factor pi Y reaches 1% of a white diffuser's:
// darker bins are seen against brighter ones, and their few paths make their colour noise.
constexpr double kLitReflectanceFactor = 0.01;

struct ColourErrorBin {
    uint32_t theta, phi;   // the bin (BinGrid)
    // reflectance factors pi f in XYZ (D65, Y = 1 for a white diffuser): the spectral run's, the other's (the RGB
    // run's or a model's)
    glm::dvec3 xyz_spectral{0}, xyz_other{0};
    ColourDifference de;
    double de2000_noise = 0;   // CIEDE2000 that the two runs' noise alone makes: the median over draws of the spectral
        // colour perturbed by each run's standard errors (what de.de2000 would be if the runs agreed in truth)
    bool lit = false;
};

struct ColourErrorSlice {   // one incident angle and side
    double theta_i_deg = 0;
    int side = 0;
    glm::dvec3 albedo_spectral{0}, albedo_other{0};   // the energy leaving through the side, XYZ
    ColourDifference albedo_de;
    size_t lit = 0;   // bins counted below
    double median_de2000 = 0, p95_de2000 = 0, max_de2000 = 0, median_de_itp = 0, p95_de_itp = 0, max_de_itp = 0;
    double median_de2000_noise = 0;
    size_t max_bin = 0;   // the lit bin of the largest CIEDE2000
    // X's, Y's and Z's median relative standard errors over the bins above 1% of the slice's peak Y, each run (upper
    // bounds: the channels a pass traces together counted as fully correlated)
    glm::dvec3 xyz_median_rse_spectral{0}, xyz_median_rse_other{0};
    std::vector<ColourErrorBin> bins;   // theta-major, as Slice
};

// The colours a spectral run is compared with, on its bins (theta-major), in XYZ: f and se in 1/sr (se 0 for a
// model), the albedo of the side.
struct OtherColours {
    std::vector<glm::dvec3> f_xyz, se_xyz;
    glm::dvec3 albedo_xyz{0};
};
// What a comparison needs of the spectral run on one angle and side, whatever it is compared with: its slice, each
// pass's se in XYZ (sum over its bands of w_b se_b: its bands fully correlated) and the side's albedo in XYZ.
struct SpectralReference {
    size_t angle = 0;
    int side = 0;
    double theta_i_deg = 0;
    uint32_t n_phi = 0;
    SpectralSlice slice;
    std::vector<std::vector<glm::dvec3>> group_se;   // [pass][bin]
    glm::dvec3 albedo{0};
};
SpectralReference spectral_reference(const SpectralResult& spectral, size_t angle, int side);
ColourErrorSlice colour_error_slice(const SpectralReference& ref, const OtherColours& other);

// rgb: the RGB run of the same stack (its materials reduced to three channels), the same angles and bins.
std::vector<ColourErrorSlice> colour_error(const SpectralResult& spectral, const SimResult& rgb);

// One slice's summary as rgb-vs-spectral.json writes it, `other` naming the colours compared ("rgb", "model").
Json colour_error_json(const ColourErrorSlice& s, const BinGrid& grid, const std::string& other);

// DIR/rgb-vs-spectral.json (the summaries, the reduction and what it clipped) and DIR/rgb-vs-spectral.csv (a row per
// bin: theta_i, side, the bin's edges, both colours, both differences, the noise, lit).
// seconds: the two runs' wall clock (spectral, RGB), from which the cost of the spectral run at equal luminance error.
void write_colour_error(const std::string& dir, const std::vector<ColourErrorSlice>& e, const SpectralResult& spectral,
                        const std::string& reduction, const std::string& reduction_notes,
                        const std::array<double, 2>& seconds);
// The spectral run's time to the RGB run's median error in X, Y and Z, over the RGB run's time to it:
// (t_s rse_s^2) / (t_r rse_r^2), each run's error falling as 1 / sqrt(paths), averaged over the slices, the largest of
// the three.
double spectral_cost_at_equal_error(const std::vector<ColourErrorSlice>& e, const std::array<double, 2>& seconds);

}   // namespace gonio
