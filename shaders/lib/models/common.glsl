// models/common.glsl: what the analytic layered models share. A model evaluates f(l, v) (1/sr, cosine
// excluded) for l, v in the upper hemisphere, z = stack normal, on two-layer opaque stacks: a dielectric coat
// (layer 0: alpha0, eta = n1/n0, optical depth tau) over a Lambertian or conductor base (layer 1); a production
// model's dielectric base is three layers, the coat over a dielectric interface (layer 1: alpha1, base_eta) over a
// Lambertian (layer 2).
// Its top-interface term uses the very same GGX and Fresnel functions as the reference (ggx.glsl,
// fresnel.glsl). Smooth interfaces (alpha = 0) are evaluated as GGX with MODEL_MIN_ALPHA, which no 1-degree
// bin can tell from a delta.
#ifndef GONIO_MODELS_COMMON_GLSL
#define GONIO_MODELS_COMMON_GLSL
#include "../compat.glsl"
#include "../fresnel.glsl"
#include "../ggx.glsl"
#include "../interface.glsl"
#include "../stack_params.glsl"

const float MODEL_MIN_ALPHA = 1e-4f;

// What a model returns for an interface kind it has no formula for (model_cannot_represent refuses such stacks):
// NaN, which every model test catches, so that a new kind cannot silently take another kind's formula.
GONIO_INLINE float model_nan() { return uintBitsToFloat(0x7fc00000u); }

// The models' conventions: bits of model_convention(), which the includer provides (0: what the model's publication
// and official code compute; a registry variant's `variant:` line sets others, host/models/model_file.h)
const uint CONVENTION_G2 = 1u;                 // height-correlated Smith G2 in the GGX lobes and the tables (Belcour's)
const uint CONVENTION_TIR_BELOW_MEDIA = 2u;    // Belcour's TIR term kept below an absorbing medium
const uint CONVENTION_DARKENING_T2 = 4u;       // OpenPBR dev_1.2's darkening, (1 - K) / (1 - K E_b T^2)
const uint CONVENTION_ROUGHENING_PR261 = 8u;   // OpenPBR PR #261's coat roughening of the base
const uint CONVENTION_REFLECTANCE_FRESNEL = 16u;   // Standard Surface's OSL reflectance(): the Fresnel at the normal
const uint CONVENTION_MATERIALX_GRAPH = 32u;   // OpenPBR's reference MaterialX graph (open_pbr_surface.mtlx)
const uint CONVENTION_COAT_FRESNEL_VH = 64u;   // the glTF Sample Viewer's coat lobe: Schlick at v.h, not n.v
const uint CONVENTION_CYCLES_4_4 = 128u;       // Blender 4.0-4.4's Principled coat: no compensation, 1 - F(mu_v) below
const uint CONVENTION_RECIPROCAL_COAT = 256u;  // adobe/openpbr-bsdf's reciprocal switch: 1 - E_c on both sides
const uint CONVENTION_SEPARABLE_G = 512u;     // OpenPBR with the separable Smith G1 G1 in its lobes and albedos
const uint CONVENTION_DARKENING_NUMERATOR = 1024u;   // OpenPBR's darkening with #269's numerator (1 - E_F) / eta^2
const uint CONVENTION_SINGLE_SCATTERING_LOBES = 2048u;   // OpenPBR's base lobes without their energy compensation

// Terms of a layered model, integrated over the bins separately (see models.comp).
const uint TERM_TOP = 1u;    // reflection off the top interface, f_r0
const uint TERM_BASE = 2u;   // everything that went through the coat (a dielectric base: its interface's lobe)
const uint TERM_DIFFUSE = 4u;   // a dielectric base's diffuse under its interface (three layers: coat, dielectric,
                                // Lambertian)
const uint TERM_ALL = TERM_TOP | TERM_BASE | TERM_DIFFUSE;

struct CoatParams {
    float alpha0;    // coat roughness (>= MODEL_MIN_ALPHA)
    float eta;       // n1 / n0
    vec3 tau;        // coat optical depth
    uint base_kind;  // KIND_LAMBERTIAN or KIND_CONDUCTOR
    float alpha1;    // base roughness (>= MODEL_MIN_ALPHA)
    vec3 base_c0;    // lambertian albedo, or conductor eta relative to the coat
    vec3 base_c1;    // conductor k relative to the coat
    float base_eta;  // a dielectric base's interface: its IOR relative to the coat's (the Lambertian under it:
                     // model_layer(2u))
};

GONIO_INLINE CoatParams coat_params(LayerGpu coat, LayerGpu base) {
    CoatParams p;
    p.alpha0 = max(layer_alpha(coat), MODEL_MIN_ALPHA);
    p.eta = layer_eta(coat);
    p.tau = layer_optical_depth(coat);
    p.base_kind = layer_kind(base);
    p.alpha1 = max(layer_alpha(base), MODEL_MIN_ALPHA);
    p.base_c0 = layer_conductor_eta(base);   // = layer_albedo(base) for a Lambertian base
    p.base_c1 = layer_conductor_k(base);
    p.base_eta = layer_eta(base);
    return p;
}

// A production model's artist parameters for a stack: its GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) hook
// (models/all.glsl) appends the values of its header's `artist-parameters:` line for the stack's shape with
// artist_value, in that line's order (a scalar in all three channels). It reads p as the stack has it (alpha0 and
// alpha1 the roughnesses as given, 0 for a smooth interface; base_kind KIND_LAMBERTIAN, KIND_CONDUCTOR, or
// KIND_DIELECTRIC for a dielectric base, base_eta its IOR relative to the coat's) and `diffuse`, the albedo of the
// Lambertian under a dielectric base, and the stack's layers through model_layer(i) (a sheen model's fibres). The CPU
// twin runs it for `gonio models STACK` (host/models/artist_parameters.cpp, model_cpu.cpp
// eval_model_artist_parameters_on).
const uint MODEL_MAX_ARTIST_PARAMETERS = 16u;
struct ArtistValues {
    vec3 value[MODEL_MAX_ARTIST_PARAMETERS];
    uint count;   // the values appended (more than MODEL_MAX_ARTIST_PARAMETERS: counted, not kept)
};
GONIO_INLINE void artist_value(INOUT(ArtistValues) a, vec3 v) {
    if (a.count < MODEL_MAX_ARTIST_PARAMETERS) a.value[a.count] = v;
    a.count += 1u;
}
GONIO_INLINE void artist_value(INOUT(ArtistValues) a, float v) { artist_value(a, vec3(v)); }

// f_r0: the exact rough dielectric reflection of the top interface (Walter et al. 2007, eq. 20), with the
// height-correlated Smith G2 of the reference.
GONIO_INLINE float top_reflection(vec3 l, vec3 v, float alpha, float eta) {
    if (l.z <= 0.0f || v.z <= 0.0f) return 0.0f;
    vec3 h = normalize(l + v);
    return fresnel_dielectric(dot(l, h), eta) * ggx_D(h, alpha) * ggx_G2(l, v, alpha) / (4.0f * l.z * v.z);
}

// The exact reflection off the stack's top interface `top` (Bati et al. 2019 section 4.2's lobe 0), with the
// reference's height-correlated G2: a conductor's Fresnel-conductor GGX lobe, a dielectric's top_reflection.
GONIO_INLINE vec3 top_interface_reflection(LayerGpu top, vec3 l, vec3 v) {
    float at = max(layer_alpha(top), MODEL_MIN_ALPHA);
    uint kind = layer_kind(top);
    if (kind == KIND_CONDUCTOR) {
        vec3 h = normalize(l + v);
        return fresnel_conductor(dot(l, h), layer_conductor_eta(top), layer_conductor_k(top)) *
               (ggx_D(h, at) * ggx_G2(l, v, at) / (4.0f * l.z * v.z));
    }
    if (kind == KIND_DIELECTRIC) return vec3(top_reflection(l, v, at, layer_eta(top)));
    return vec3(model_nan());   // a Lambertian top: no model takes it
}

// The base BRDF at directions inside the coat (pointing away from the base), with roughness alpha.
GONIO_INLINE vec3 base_brdf(CoatParams p, vec3 l1, vec3 v1, float alpha) {
    if (l1.z <= 0.0f || v1.z <= 0.0f) return vec3(0.0f);
    if (p.base_kind == KIND_LAMBERTIAN) return p.base_c0 * INV_PI;
    // a conductor; any other kind has no formula here (model_cannot_represent refuses it): NaN, which every
    // model test catches, rather than another kind's formula
    if (p.base_kind != KIND_CONDUCTOR) return vec3(model_nan());
    vec3 h = normalize(l1 + v1);
    return fresnel_conductor(dot(l1, h), p.base_c0, p.base_c1) *
           (ggx_D(h, alpha) * ggx_G2(l1, v1, alpha) / (4.0f * l1.z * v1.z));
}

// A conductor's reflectance at normal incidence, ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), n and k relative to the medium
// it is seen from: the F0 a production model's metal takes (gltf-clearcoat, openpbr: in the exterior)
GONIO_INLINE vec3 conductor_normal_reflectance(vec3 n, vec3 k) {
    return ((n - 1.0f) * (n - 1.0f) + k * k) / ((n + 1.0f) * (n + 1.0f) + k * k);
}

// Snell refraction through the macro-normal into the coat, returned pointing away from the base.
GONIO_INLINE vec3 refract_into_coat(vec3 w, float eta) {
    vec3 t = vec3(w.x / eta, w.y / eta, 0.0f);
    t.z = sqrt(max(0.0f, 1.0f - t.x * t.x - t.y * t.y));
    return t;
}

// Beer-Lambert for the trip down along l1 and up along v1.
GONIO_INLINE vec3 coat_attenuation(vec3 tau, vec3 l1, vec3 v1) {
    return exp(-tau * (1.0f / max(l1.z, 1e-6f) + 1.0f / max(v1.z, 1e-6f)));
}
#endif
