// models/user_model.glsl: what a model written as one file sees (docs/MODELS.md, "Your own model"), and how
// models.comp calls it. models.comp includes this file in place of models/all.glsl when the host compiles a user's
// model at run time (host/models/user_model.cpp: GONIO_USER_MODEL defined, the user's file as
// "gonio_user_model.glsl").
//
// The file defines   vec3 model_f(vec3 l, vec3 v)
// f(l, v) in 1/sr, the cosine excluded, RGB; z is the stack normal, l and v point away from the surface, l is where
// the light comes from; v.z < 0 is the transmission side (transmissive stacks). It may read the stack through
// gonio_layer_count(), gonio_layer(i) (0 the top layer: files and the command line number from 1; beyond the last,
// NaN) and
// gonio_exterior_ior(), and include the reference's own functions: "ggx.glsl" (ggx_D, ggx_lambda, ggx_G1, ggx_G2,
// ggx_G2_separable), "fresnel.glsl" (fresnel_dielectric(cos, eta), fresnel_conductor(cos, eta, k), relative
// indices), "interface.glsl", "models/common.glsl" (top_reflection, refract_into_coat, ...).
// Names beginning with gonio_, model_, quad_, GONIO_, MODEL_, LOBE_, QUAD_ and the kernel's buffers are gonio's.
//
// The file may also define its lobe hints, so that the bin integration grades its pieces towards them:
//     uint model_lobes(vec3 l, out GonioLobe lobes[GONIO_MAX_LOBES])
// For light from l it fills lobes[0 .. n-1] and returns n (0 to GONIO_MAX_LOBES): each narrow lobe's peak direction
// (away from the surface; direction.z < 0 on the transmission side; any length but 0) and GGX roughness. Roughness 0
// is a delta lobe, which model_f leaves out: its weight (RGB, the share of the light from l that leaves in that one
// direction, what a smooth interface's Fresnel reflectance is) goes whole into the bin of its direction, as the
// built-in models book theirs (models.comp). The host sees the definition (a line beginning "uint model_lobes(") and
// compiles with GONIO_MODEL_HINTS. A NaN or infinite direction, a zero one, a negative roughness, a delta's NaN,
// infinite or negative weight or n > GONIO_MAX_LOBES makes the model's values unusable, as a NaN value does.
#ifndef GONIO_USER_MODEL_GLSL
#define GONIO_USER_MODEL_GLSL
#include "common.glsl"
#include "stack_tables.glsl"   // model_parameter(i): the file's own parameters, as param_NAME

const uint GONIO_DIELECTRIC = KIND_DIELECTRIC;
const uint GONIO_CONDUCTOR = KIND_CONDUCTOR;
const uint GONIO_LAMBERTIAN = KIND_LAMBERTIAN;
const uint GONIO_NO_LAYER = 0xffffffffu;   // gonio_layer(i) beyond the stack's layers
// A medium's phase function (GonioLayer.phase): medium.glsl's MEDIUM_PHASE_* (not included here, so that its names
// stay out of a user's file; tests/test_microflakes.cpp checks the values are those)
const uint GONIO_PHASE_HG = 0u;           // Henyey-Greenstein, of phase_g
const uint GONIO_PHASE_SGGX_FIBRE = 1u;   // SGGX fibres along the normal, of fibre_roughness
const uint GONIO_PHASE_SGGX_FLAKE = 2u;   // SGGX flakes facing the normal, of fibre_roughness

// A lobe hint (model_lobes above).
struct GonioLobe {
    vec3 direction;   // the lobe's peak, away from the surface
    float roughness;   // its GGX alpha, 0: a delta lobe (not in model_f)
    vec3 weight;   // a delta lobe's: the share of the light in that direction, RGB (ignored for roughness > 0)
};
const uint GONIO_MAX_LOBES = GONIO_MAX_HINTS;

// A layer as the stack file gives it: an interface and, for a dielectric, the medium under it.
struct GonioLayer {
    uint kind;   // GONIO_DIELECTRIC, GONIO_CONDUCTOR or GONIO_LAMBERTIAN
    float roughness;   // GGX alpha of the interface (0: smooth)
    vec3 ior;   // absolute index of refraction: a dielectric's (the same in every channel), a conductor's n
    vec3 k;   // a conductor's extinction coefficient (0 otherwise)
    float eta;   // a dielectric: its index over the index above it (what fresnel_dielectric takes)
    vec3 optical_depth;   // a dielectric: extinction optical depth of the medium under it, per channel
    vec3 scattering_albedo;   // a dielectric: single-scattering albedo of that medium (0: absorbing only)
    float phase_g;   // a dielectric: Henyey-Greenstein g of that medium
    uint phase;   // a dielectric: that medium's phase function, GONIO_PHASE_HG or an SGGX microflakes' (medium.glsl)
    float fibre_roughness;   // a dielectric: the microflakes' alpha of that medium (0 where it is Henyey-Greenstein's)
    vec3 albedo;   // a Lambertian base's albedo
};

uint gonio_layer_count() { return model_layer_count(); }
float gonio_exterior_ior() { return stack_exterior_ior(u_stack.info); }
// Layer i (0: the top). The device holds indices relative to the medium above (stack_params.glsl); the absolute
// ones are the exterior's times the dielectrics' relative indices above. A layer the stack does not have (i at or
// beyond gonio_layer_count(): a file without `represents:` runs on every stack) is all NaN, kind GONIO_NO_LAYER, so
// that a model reading it returns NaN, which gonio reports with where, rather than values from beyond the stack.
GonioLayer gonio_layer(uint i) {
    if (i >= gonio_layer_count()) {
        float nan = uintBitsToFloat(0x7fc00000u);
        return GonioLayer(GONIO_NO_LAYER, nan, vec3(nan), vec3(nan), nan, vec3(nan), vec3(nan), nan, 0xffffffffu, nan,
                          vec3(nan));
    }
    float above = gonio_exterior_ior();
    for (uint j = 0u; j < i; ++j)
        if (layer_kind(model_layer(j)) == KIND_DIELECTRIC) above *= layer_eta(model_layer(j));
    LayerGpu L = model_layer(i);
    GonioLayer g;
    g.kind = layer_kind(L);
    g.roughness = layer_alpha(L);
    g.ior = vec3(0.0f);
    g.k = vec3(0.0f);
    g.eta = 0.0f;
    g.optical_depth = vec3(0.0f);
    g.scattering_albedo = vec3(0.0f);
    g.phase_g = 0.0f;
    g.phase = GONIO_PHASE_HG;
    g.fibre_roughness = 0.0f;
    g.albedo = vec3(0.0f);
    if (g.kind == KIND_DIELECTRIC) {
        g.eta = layer_eta(L);
        g.ior = vec3(above * g.eta);
        g.optical_depth = layer_optical_depth(L);
        g.scattering_albedo = layer_scattering_albedo(L);
        g.phase_g = layer_phase_g(L);
        g.phase = layer_medium_phase(L);
        g.fibre_roughness = layer_microflake_alpha(L);
    } else if (g.kind == KIND_CONDUCTOR) {
        g.ior = above * layer_conductor_eta(L);
        g.k = above * layer_conductor_k(L);
    } else {
        g.albedo = layer_albedo(L);
    }
    return g;
}

#include "gonio_user_model.glsl"

// models.comp's call: a user's model is one term (TERM_ALL), integrated as a black box
// (host/models/model_plan.cpp plan_black_box)
vec3 eval_model(uint model, CoatParams p, uint terms, vec3 l, vec3 v) { return model_f(l, v); }
#endif
