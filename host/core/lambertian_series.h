// lambertian_series.h: the Lambertian series, the walk's exact shortcut for a dielectric coat over a Lambertian base
// (docs/PHYSICS.md, "The Lambertian series"; shaders/lib/walk.glsl).
//
// Light leaving a Lambertian base has forgotten where it came from: whatever its history, it leaves with the cosine
// density. So every trip base -> coat -> (out, or back to the base) is alike, and per unit of energy leaving the
// base, one trip lets `escaped` out, returns `returned` to the base (which sends albedo x returned up again) and
// loses `lost` to single-scattering microfacet loss (per channel; the rest is absorbed by the coat's medium). All
// trips together let escaped x S out and lose lost x S, with S = 1 / (1 - albedo returned). The walk therefore
// traces one trip and weighs an exit by S: unbiased, with three events at most, so lavapipe's SIMD lanes do not
// wait for the longest of eight paths (docs/PERFORMANCE.md).
//
// `returned` and `lost` are integrals over the cosine density and the coat's visible normals, computed here by
// tensor-product quadrature with the walk's own functions (shaders/lib/interface.glsl through the CPU twin).
#pragma once
#include "compat.glsl"
#include "stack.h"
#include "stack_params.glsl"   // StackGpu

#include <glm/glm.hpp>
#include <string>

namespace gonio {

// One trip, per unit of energy leaving the base with the cosine density (per channel).
struct SeriesTrip {
    glm::dvec3 escaped{0.0}, returned{0.0}, lost{0.0};
};

// The trip's integrals: quadrature in s = sin^2 theta of the direction leaving the base (Gauss-Legendre panels split
// at the coat's critical angle and around it by its roughness), the visible normal's azimuth (midpoint rule,
// periodic) and height (Gauss-Legendre panels split where the integrand has kinks); `refine` scales every node count.
// The stack (packed, as the walk reads it: pack_stack) must be a dielectric coat over a Lambertian base.
SeriesTrip lambertian_trip(const StackGpu& s, double refine = 1.0);

struct LambertianSeries {
    bool applies = false;
    std::string reason;   // why not, where it does not apply
    SeriesTrip trip;
    glm::dvec3 gain{1.0};   // S = 1 / (1 - albedo returned)
    glm::dvec3 lost_all{0.0};   // lost S: microfacet loss of all trips per unit leaving the base
    // Emission from the base: cosine density within the coat's escape cone (sin^2 of its half-angle cone_sin2) with
    // probability cone_prob, else over the hemisphere; weights factor_in / factor_out (sample_lambertian_series).
    double cone_sin2 = 1.0, cone_prob = 0.0, factor_in = 1.0, factor_out = 1.0;
    double quadrature_error = 0.0;   // estimated error of the trip's terms (difference from a coarser rule)
    double relative_error = 0.0;   // the resulting relative error bound on the diffuse exits (escaped x S)
    double max_weight = 1.0;   // bound on an exiting path's weight (channel)
    int weight_shift = 0;   // staging holds weight x 2^-shift (bins.glsl, fold.comp)
};

// The largest bound on an exiting weight the series accepts (energy-book entries must stay below 128, bins.glsl):
// beyond it (a nearly lossless coat that traps nearly everything) the walk traces every trip instead.
inline constexpr double kMaxSeriesWeight = 64.0;
// The largest estimated relative error the series may add to the diffuse exits (beyond it the walk traces every
// trip): 1e-4, a hundred times below the 1% relative standard error a converged reference bin reaches.
inline constexpr double kMaxSeriesRelativeError = 1e-4;

// Whether the series applies to the stack (packed, as the walk reads it: walk_stack computes it, WalkStack::series)
// (a two-layer dielectric-over-Lambertian stack whose weight bound stays within kMaxSeriesWeight and whose
// quadrature error within kMaxSeriesRelativeError) and its terms. Memoised per coat and albedo (0.1 to 0.5 s of
// quadrature the first time).
LambertianSeries lambertian_series(const StackGpu& g);

}   // namespace gonio
