// microsurface.glsl: a rough interface's microsurface statistics, chosen per interface by the stack's
// `distribution`, `shadowing` and `microfacets` keys (docs/PHYSICS.md, "Interfaces"): the microfacet distribution (GGX,
// the default, or Beckmann), Smith's masking-shadowing (height-correlated, the default, or separable G1 G1) and whether
// light scatters once on the microsurface or walks on it (microsurface_walk.glsl). `micro` holds them (MICROSURFACE_*
// bits; 0 is GGX with height-correlated Smith, single scattering, whose code these functions then are, bit for bit,
// where the caller's micro is a compile-time 0).
#ifndef GONIO_MICROSURFACE_GLSL
#define GONIO_MICROSURFACE_GLSL
#include "compat.glsl"
#include "ggx.glsl"
#include "beckmann.glsl"

// The walk's SPIR-V is built in variants (CMakeLists.txt; host/reference/walk_spirv.cpp): with
// GONIO_WALK_STATISTICS 0 the functions below are GGX with height-correlated Smith whatever micro says, and Beckmann's
// code is not in the shader at all; with GONIO_WALK_MULTIPLE 0 the walk on the microsurface is not (walk.glsl). A
// specialisation constant folds such code away too, but only after lavapipe has inlined every call: dead code still
// costs the JIT its time, at every run's start. Everything else (the models, the CPU twin) keeps all of it.
#ifndef GONIO_WALK_STATISTICS
#define GONIO_WALK_STATISTICS 1
#endif
#ifndef GONIO_WALK_MULTIPLE
#define GONIO_WALK_MULTIPLE 1
#endif

const uint MICROSURFACE_BECKMANN = 1u;    // else GGX
const uint MICROSURFACE_SEPARABLE = 2u;   // else height-correlated Smith
// The bits of interface k in a WalkSpec's microsurface_mask (MICROSURFACE_MASK): 2 per interface, the statistics
const uint MICROSURFACE_BITS = 2u;
const uint MICROSURFACE_STATISTICS = 3u;   // the bits the single-scattering functions below read
// Light walks on the microsurface (Heitz et al. 2016; microsurface_walk.glsl), always height-correlated. In a layer's
// code (layer_microsurface) only; a WalkSpec holds it apart, one bit per interface (multiple_mask, MULTIPLE_MASK)
const uint MICROSURFACE_MULTIPLE = 4u;

GONIO_INLINE bool microsurface_beckmann(uint micro) { return (micro & MICROSURFACE_BECKMANN) != 0u; }
GONIO_INLINE bool microsurface_separable(uint micro) { return (micro & MICROSURFACE_SEPARABLE) != 0u; }
GONIO_INLINE bool microsurface_multiple(uint micro) { return (micro & MICROSURFACE_MULTIPLE) != 0u; }

// m from the visible normals D_wi (wi.z > 0).
GONIO_INLINE vec3 sample_visible_normal(vec3 wi, float alpha, uint micro, float u1, float u2) {
#if GONIO_WALK_STATISTICS
    if (microsurface_beckmann(micro)) return sample_beckmann_visible_normal(wi, alpha, u1, u2);
#endif
    return sample_ggx_visible_normal(wi, alpha, u1, u2);
}

GONIO_INLINE float visible_normal_pdf(vec3 wi, vec3 m, float alpha, uint micro) {
#if GONIO_WALK_STATISTICS
    if (microsurface_beckmann(micro)) return beckmann_visible_normal_pdf(wi, m, alpha);
#endif
    return ggx_visible_normal_pdf(wi, m, alpha);
}

GONIO_INLINE float microsurface_lambda(vec3 w, float alpha, uint micro) {
#if GONIO_WALK_STATISTICS
    if (microsurface_beckmann(micro)) return beckmann_lambda(w, alpha);
#endif
    return ggx_lambda(w, alpha);
}

// The weight of visible-normal sampling, G2(wi, wo) / G1(wi): height-correlated (1 + L_i) / (1 + L_i + L_o),
// separable G1(wo) = 1 / (1 + L_o). GGX height-correlated through ggx_G2_over_G1 (its one-division form).
GONIO_INLINE float microsurface_G2_over_G1(vec3 wi, vec3 wo, float alpha, uint micro) {
#if GONIO_WALK_STATISTICS
    if (micro == 0u) return ggx_G2_over_G1(wi, wo, alpha);
    float lo = microsurface_lambda(wo, alpha, micro);
    if (microsurface_separable(micro)) return 1.0f / (1.0f + lo);
    float li = microsurface_lambda(wi, alpha, micro);
    return (1.0f + li) / (1.0f + li + lo);
#else
    return ggx_G2_over_G1(wi, wo, alpha);
#endif
}
#endif
