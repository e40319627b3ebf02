#include "stack_gpu.h"
#include "kernel_interface.glsl"
#include "lambertian_series.h"
#include "microsurface.glsl"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gonio {

uint layer_microsurface_code(const Layer& L) {
    if (L.roughness <= 0.0f || L.kind == InterfaceKind::Lambertian) return 0u;
    return (L.distribution == MicrofacetDistribution::Beckmann ? MICROSURFACE_BECKMANN : 0u) |
           (L.shadowing == Shadowing::Separable ? MICROSURFACE_SEPARABLE : 0u) |
           (L.microfacets == Microfacets::Multiple ? MICROSURFACE_MULTIPLE : 0u);
}

StackGpu pack_stack(const Stack& s) {
    StackGpu g{};
    // y: histogram sides; z: the exterior's absolute IOR (a user's model reads it, the walk does not)
    g.info = vec4(float(s.layers.size()), s.transmissive() ? 2.0f : 1.0f, s.exterior_ior, 0.0f);
    g.series.gain = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    g.series.lost = vec4(0.0f);
    g.series.emit = vec4(1.0f, 0.0f, 1.0f, 1.0f);
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& L = s.layers[i];
        glm::vec3 above = s.ior_above(i);
        LayerGpu& o = g.layers[i];
        float eta = L.ior.x / above.x;
        o.p0 = vec4(float(int(L.kind)), L.roughness, eta, eta != 0.0f ? 1.0f / eta : 0.0f);
        o.tau = vec4(L.optical_depth, 0.0f);
        const float micro = float(layer_microsurface_code(L));   // 0 on every stack that keeps GGX, height-correlated
        if (L.kind == InterfaceKind::Conductor) {
            o.c0 = vec4(L.ior / above, 0.0f);
            o.c1 = vec4(L.k / above, micro);
        } else if (L.kind == InterfaceKind::Lambertian) {
            o.c0 = vec4(L.albedo, 0.0f);
        } else if (s.medium_scatters(i)) {
            o.c0 = vec4(L.scattering_albedo, L.phase_g);
            // 0, 0 in a Henyey-Greenstein medium (every stack without the phase key: its bytes unchanged)
            o.c1 = vec4(float(int(L.phase)), L.phase == MediumPhase::Hg ? 0.0f : L.fibre_roughness, 0.0f, 0.0f);
        }
        if (L.kind == InterfaceKind::Dielectric) o.c1.w = micro;
    }
    return g;
}

namespace {

// The specialisation but the series (which the caller decides where series_allowed).
WalkSpec walk_shape(const Stack& s, bool specialised) {
    WalkSpec w;
    w.specialised = specialised;
    w.layer_count = uint(s.layers.size());
    w.base_kind = uint(int(s.base().kind));
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& L = s.layers[i];
        if (L.roughness > 0.0f) w.rough_mask |= 1u << i;
        const uint micro = layer_microsurface_code(L);
        w.microsurface_mask |= (micro & MICROSURFACE_STATISTICS) << (MICROSURFACE_BITS * i);
        if (micro & MICROSURFACE_MULTIPLE) w.multiple_mask |= 1u << i;
        if (s.medium_scatters(i)) {
            w.scatter_mask |= 1u << i;
            if (L.phase != MediumPhase::Hg) w.microflake_mask |= 1u << i;
        } else if (L.optical_depth.x > 0.0f || L.optical_depth.y > 0.0f || L.optical_depth.z > 0.0f) {
            w.absorb_mask |= 1u << i;
        }
    }
    return w;
}

bool series_allowed(bool specialised, bool series, bool orders, uint32_t max_events) {
    return specialised && series && !orders && max_events >= 3;
}

// The booking estimators (trace_book.glsl) where they apply and `branching` allows them (w.series decided first), on
// a specialised walk whose top interface is a dielectric coat, but not with the Lambertian series. The entry's both
// branches over an opaque base where the coat is rough (over a smooth one every path would book the same F in the one
// mirror bin: a bin without variance, which the verdicts' cells cannot weigh). The exit estimate on two interfaces
// with no medium that scatters, over a conductor base or a slab's dielectric base, one of the two rough (over smooth
// ones the estimate is the path's own exit less its Fresnel choice, and a delta lobe on a bin's edge would fall on
// either side by the last bit of two ways of computing it). How many fresh estimates: one over a conductor (its
// estimate costs a conductor and a coat event; more did not pay on metallic paint), six through a slab's rough base
// (one event each, and the slab's median bins are the direct transmission they estimate; through a smooth base every
// fresh estimate is the same refraction: one). Where they pay, measured: docs/PERFORMANCE.md, "Booking estimators".
constexpr uint32_t kSlabExitEstimates = 6;
static_assert(kSlabExitEstimates <= MAX_EXIT_ESTIMATES, "trace_book.glsl holds at most MAX_EXIT_ESTIMATES");

void choose_booking(const Stack& s, bool branching, WalkSpec& w) {
    // (neither where light walks on a microsurface: both branches and the exit estimate sample single scattering)
    const bool coat = branching && w.specialised && s.layers.size() >= 2 &&
                      s.layers[0].kind == InterfaceKind::Dielectric && !w.series && w.multiple_mask == 0;
    w.entry_branch = coat && !s.transmissive() && (w.rough_mask & 1u) != 0;
    const InterfaceKind base = s.base().kind;
    const bool estimate = coat && w.layer_count == 2 && w.scatter_mask == 0 && w.rough_mask != 0 &&
                          (base == InterfaceKind::Conductor || base == InterfaceKind::Dielectric);
    const bool base_rough = ((w.rough_mask >> 1) & 1u) != 0;
    w.exit_estimates = !estimate ? 0u : (base == InterfaceKind::Dielectric && base_rough ? kSlabExitEstimates : 1u);
}

}   // namespace

WalkSpec walk_spec(const Stack& s, bool specialised, bool series, bool orders, uint32_t max_events, bool branching) {
    return walk_stack(s, specialised, series, orders, max_events, branching).spec;
}

bool can_bake_stack(const WalkSpec& ws) { return ws.specialised && ws.layer_count <= 2 && ws.scatter_mask == 0; }

WalkStack walk_stack(const Stack& s, bool specialised, bool series, bool orders, uint32_t max_events, bool branching) {
    WalkStack w;
    w.spec = walk_shape(s, specialised);
    w.gpu = pack_stack(s);
    w.series = lambertian_series(w.gpu);
    if (series_allowed(specialised, series, orders, max_events)) {
        const LambertianSeries& ls = w.series;
        w.spec.series = ls.applies;
        if (ls.applies) {
            w.gpu.series.gain = vec4(float(ls.gain.x), float(ls.gain.y), float(ls.gain.z), 1.0f);
            w.gpu.series.lost = vec4(float(ls.lost_all.x), float(ls.lost_all.y), float(ls.lost_all.z), 0.0f);
            w.gpu.series.emit =
                vec4(float(ls.cone_sin2), float(ls.cone_prob), float(ls.factor_in), float(ls.factor_out));
            w.weight_shift = ls.weight_shift;
        }
    }
    choose_booking(s, branching, w.spec);
    // a path's bookings in one bin: the entry's reflected branch (at most 1) and the rest of the path (at most 1),
    // so weights up to 2 (trace_book.glsl)
    if (w.spec.entry_branch || w.spec.exit_estimates > 0) w.weight_shift = std::max(w.weight_shift, 1);
    w.set_staging_shift(w.weight_shift);
    return w;
}

void WalkStack::set_staging_shift(int shift) {
    if (shift < weight_shift) throw std::invalid_argument("WalkStack: the staging scale is too small for this stack");
    staging_shift = shift;
    gpu.series.gain.w = std::ldexp(1.0f, -shift);
}

}   // namespace gonio
