// gonio-model: enterprise-pbr
// citation: Dassault Systemes Enterprise PBR Shading Model 2025x (DassaultSystemes-Technology/
//   EnterprisePBRShadingModel spec-2025x.md.html @28d1c266: "Clearcoat", "Microfacet BSDF", "Dielectric BSDF for
//   Opaque Surfaces", "Diffuse BRDF"), clearcoat c = 1 over its opaque dielectric with specular s = 0
// family: production
// summary: Core (1 - max(F_c(v.n), F_c(l.n))) + F_c(h.v) M_c: a colourless coat of IOR 1.5 whose Schlick Fresnel
//   weighs its GGX lobe at h.v and takes the larger of its Fresnels at v and l from the core (reciprocal), over a
//   Lambertian core; no refraction, absorption or inter-reflection
// stacks: one colourless dielectric coat of relative IOR 1.5 over a Lambertian base
// mapping: clearcoat c = 1, clearcoat roughness r_c = sqrt(alpha_coat) (the coat's IOR fixed at 1.5); a Lambertian of
//   albedo A: metallic m = 0, transparency t = 0, translucency l = 0, specular s = 0, albedo rho = A
// artist-parameters: coat-over-lambertian = clearcoat, clearcoat roughness, metallic, transparency, translucency,
//   specular, albedo (colour)
// represents: coat-over-lambertian
// reciprocal: yes
// energy-conserving: no (not by construction: the coat lobe's Schlick Fresnel at h.v and the core's
//   1 - max(F_c(v.n), F_c(l.n)) are not each other's complement; over a white Lambertian no excess found, largest
//   0.980 at coat alpha 0.01 and 75 degrees, and at 89.9 degrees it returns 0.09-0.42 of the light)
// plan: coat
// refuses: scattering-medium = {id} has no scattering medium ({layer})
// refuses: absorbing-medium = {id}: the clearcoat is colourless ({layer}); Enterprise PBR's clearcoat has no colour
//   or thickness to give it
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: not-two-layers = {id} is one coat over one base; this stack has {layers} layers
// refuses: coat-ior-not-1.5 = {id}: the clearcoat's IOR is fixed at 1.5 (F_c(0) = 0.04); this coat's IOR relative to
//   the exterior is {coat_eta}
// refuses: base-not-lambertian = {id} takes a Lambertian base here (its opaque dielectric with specular 0), not a
//   {base}: its metal's multiple-scattering compensation needs the GGX albedo tables E_m, E_m,avg of the base's
//   roughness, which gonio does not compute yet
//
// models/builtin/10-enterprise-pbr.glsl: `enterprise-pbr`, the clearcoat of Dassault Systemes' Enterprise PBR 2025x
// over its core, as the specification computes it:
//   Coated = Core (1 - c max(F_c(v.n_c), F_c(l.n_c))) + M_c c F_c(h.v),   F_c(mu) = 0.04 + 0.96 (1 - mu)^5
// with c = 1, the clearcoat normal the surface's, and M_c = D G / (4 |v.n| |l.n|) the GGX microfacet BRDF with
// alpha = r_c^2 and the height-correlated Smith G of "Microfacet BSDF" (1 / (1 + Lambda(v) + Lambda(l))). The max of
// the two Fresnels makes the coat reciprocal (the question of Enterprise PBR issue #39). The core: the opaque
// dielectric at s = 0 is B = B_u (1 - s) + s B_c = B_u = rho / pi (translucency 0): its microfacet and
// multiple-scattering terms are weighted by s and vanish.
#ifndef GONIO_MODEL_ENTERPRISE_PBR_GLSL
#define GONIO_MODEL_ENTERPRISE_PBR_GLSL
#include "models/common.glsl"

// Schlick's Fresnel of the clearcoat, IOR 1.5: 0.04 + 0.96 (1 - |cos|)^5 (1 - |cos| clamped at 0: rounding takes |h.v|
// above 1 at h = v)
GONIO_INLINE float enterprise_clearcoat_fresnel(float c) {
    const float x = max(0.0f, 1.0f - abs(c)), x2 = x * x;
    return 0.04f + 0.96f * x2 * x2 * x;
}

GONIO_INLINE vec3 model_enterprise_pbr(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    if ((terms & TERM_TOP) != 0u) {
        const vec3 h = normalize(l + v);
        f += vec3(enterprise_clearcoat_fresnel(dot(h, v)) * ggx_D(h, p.alpha0) * ggx_G2(l, v, p.alpha0) /
                  (4.0f * l.z * v.z));
    }
    if ((terms & TERM_BASE) != 0u)
        f += p.base_c0 * INV_PI *
             (1.0f - max(enterprise_clearcoat_fresnel(v.z), enterprise_clearcoat_fresnel(l.z)));
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void enterprise_pbr_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);              // clearcoat
    artist_value(a, sqrt(p.alpha0));    // clearcoat roughness
    artist_value(a, 0.0f);              // metallic
    artist_value(a, 0.0f);              // transparency
    artist_value(a, 0.0f);              // translucency
    artist_value(a, 0.0f);              // specular
    artist_value(a, p.base_c0);         // albedo
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) enterprise_pbr_artist_parameters(p, diffuse, a)
#endif
