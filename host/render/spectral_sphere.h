// spectral_sphere.h: a spectral run on the sphere (gonio render --spectral, docs/RENDER.md): the reference's table
// from its bins' colour, and how far two renders of the sphere are apart in colour, pixel by pixel.
//
// The environment is an RGB map, so the sphere is lit per sRGB channel: a bin's colour enters as its linear sRGB under
// D65 (its reflectance's colour seen in daylight), multiplied channel by channel by the environment's radiance, as an
// RGB table is. That is exact for an environment whose colour is D65's white and an approximation for a tinted one,
// which the spectral and the RGB table share: what differs between them is the material's colour.
#pragma once

#include "image.h"
#include "reference_render.h"
#include "spectral_output.h"

#include <cstddef>

namespace gonio {

// The table of two spectral runs of the same stack, bins and angles (independent halves, other seeds): each bin's
// linear sRGB (spectral_slice).
ReferenceTable table_from_spectral_halves(const SpectralResult& a, const SpectralResult& b);

// A perfect white diffuser (f = 1/pi in every bin) on t's bins and angles: rendered, each pixel is the radiance a
// white diffuser shows there, the white the pixel's colour is measured against.
ReferenceTable white_diffuser_table(const ReferenceTable& t);

// Pixel by pixel, CIEDE2000 and Delta E_ITP between two renders, each pixel's XYZ over the white diffuser's Y there
// (its reflectance factor, colour_difference.h). A pixel counts where it is on the sphere, the white is lit and the
// first render's Y reaches kLitReflectanceFactor of the white's. The noise floor per pixel: the two renders'
// differences between their own halves, sqrt(dE_a^2 + dE_b^2) / 2 (a full render's noise is half its halves'
// difference, and the two renders' noises add).
struct SphereColourError {
    Image de2000, de_itp, noise;   // per pixel the value in R, G and B; A = 1 where it counts
    size_t lit = 0;
    double median_de2000 = 0, p95_de2000 = 0, max_de2000 = 0;
    double median_de_itp = 0, p95_de_itp = 0, max_de_itp = 0;
    double median_noise = 0;
};
SphereColourError sphere_colour_error(const ReferenceRender& a, const ReferenceRender& b, const Image& white);

}   // namespace gonio
