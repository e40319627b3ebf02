// spectral_output.h: the files of a spectral run (gonio simulate --spectral, docs/SPECTRAL.md): its bands' bins, their
// colour (CIE 1931 XYZ under D65, linear sRGB) and the energy book per band.
#pragma once

#include "exr_parts.h"
#include "reference.h"
#include "spectral_bands.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace gonio {

// A spectral run: band b was traced as channel b % 3 of groups[b / 3] (three bands per pass of the RGB walk).
struct SpectralResult {
    Stack stack;   // as the file gives it (its materials named)
    SpectralBands bands;
    std::vector<SimResult> groups;
    double seconds = 0;
};

// One angle and side of the run: per bin, each band's f and se, and the colour.
struct SpectralSlice {
    std::vector<std::vector<double>> f, se;   // [band][bin], 1/sr
    std::vector<glm::dvec3> xyz, xyz_se, srgb;   // per bin; xyz_se an upper bound (bands traced together counted
        // as fully correlated)
};
SpectralSlice spectral_slice(const SpectralResult& r, size_t angle, int side);

// DIR/<name>.exr: one part per incident angle and side, channels X, Y, Z, se.X, se.Y, se.Z (the bins in XYZ, 1/sr),
// R, G, B (linear sRGB) and band.NNN, se.band.NNN per band (NNN its centre in nm).
void write_spectral_exr(const std::string& path, const SpectralResult& r);
// Its parts in memory (the Python module's spectral runs), each n_theta x n_phi.
std::vector<ExrPart> spectral_exr_parts(const SpectralResult& r);
// DIR/summary.json: the run (stack, seed, bands, device) and per angle the energy book per band ("spectral") and in
// XYZ and sRGB ("xyz", "srgb"): a perfect white reflector has reflected Y = 1.
void write_spectral_summary(const std::string& path, const SpectralResult& r);
// Its JSON in memory (json_text gives the file's bytes).
nlohmann::ordered_json spectral_summary_json(const SpectralResult& r);

}   // namespace gonio
