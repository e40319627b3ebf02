// gonio-model: gltf-clearcoat
// citation: glTF 2.0 KHR_materials_clearcoat (ratified; KhronosGroup/glTF
//   extensions/2.0/Khronos/KHR_materials_clearcoat/README.md @77b44be7, lines 89-144) over the glTF 2.0 metal-rough
//   BRDF (specification/2.0/Specification.adoc @77b44be7, Appendix B lines 3088-3248)
// family: production
// summary: mix(base, clearcoat_brdf, Fc(n.v)): a colourless coat of IOR 1.5 whose Schlick Fresnel at n.v weighs
//   its GGX lobe and takes 1 - Fc(n.v) from the base (a Lambertian base with specular off, or a metal of F0 its
//   normal-incidence reflectance); no refraction, no absorption, no inter-reflection
// stacks: one colourless dielectric coat of relative IOR 1.5 over a Lambertian, a conductor, or a dielectric interface
//   over a Lambertian (its dielectric base)
// mapping: clearcoat 1, clearcoatRoughness = sqrt(alpha_coat) (the coat's IOR fixed at 1.5); a Lambertian of albedo
//   A: metallic 0, baseColor A, KHR_materials_specular specularFactor 0; a conductor: metallic 1, baseColor F0 =
//   ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), n and k relative to the exterior, roughness = sqrt(alpha_base); a
//   dielectric interface over a Lambertian of albedo A: metallic 0, baseColor A, KHR_materials_ior ior = n_base /
//   n_exterior, KHR_materials_specular specularFactor 1, specularColorFactor 1, roughness = sqrt(alpha_base)
// artist-parameters: coat-over-lambertian = clearcoat, clearcoatRoughness, metallic, baseColor (colour),
//   specularFactor
// artist-parameters: coat-over-conductor = clearcoat, clearcoatRoughness, metallic, baseColor (colour), roughness
// artist-parameters: coat-over-dielectric-over-lambertian = clearcoat, clearcoatRoughness, metallic,
//   baseColor (colour), ior, specularFactor, specularColorFactor (colour), roughness
// represents: coat-over-lambertian, coat-over-conductor, coat-over-dielectric-over-lambertian
// reciprocal: no
// energy-conserving: no (the coat's Fresnel is taken at n.v for every l: at grazing light the coat lobe, weighed by
//   Fc near 1, adds to a base still weighed by 1 - Fc(v) near 1 elsewhere)
// variant: +viewer = convention coat-fresnel-vh: as the glTF Sample Viewer computes it for punctual lights
//   (KhronosGroup/glTF-Sample-Viewer source/Renderer/shaders/punctual.glsl @6386b1d8 getPunctualRadianceClearCoat,
//   brdf.glsl @00536c7d BRDF_specularGGX, pbr.frag @31732a89 "Layer blending"): the coat lobe weighed by its own
//   Schlick Fresnel at v.h, 0.04 + 0.96 (1 - v.h)^5, the base still by 1 - Fc(n.v)
// variant-energy-note: +viewer = the coat lobe's Fresnel at v.h and the base's 1 - Fc(n.v) are not each other's
//   complement: at grazing light the lobe, weighed by F(v.h), adds to a base weighed by 1 - Fc(v) near 1
//   elsewhere (1.008 from the light at 75 degrees over white under a coat of alpha 0.3, test_model_furnaces)
// plan: coat
// refuses: scattering-medium = {id} has no scattering medium ({layer})
// refuses: not-coat-over-base = {id} is one coat over one base (a Lambertian, a conductor, or a dielectric interface
//   over a Lambertian); this stack has {layers} layers
// refuses: absorbing-base-medium = {id}'s dielectric base has no medium between its specular and its diffuse ({layer})
// refuses: absorbing-medium = {id}: glTF's clearcoat is colourless ({layer}); KHR_materials_clearcoat has no coat
//   colour or thickness to give it
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian base (glTF's diffuse with specular off) or
//   a conductor (glTF's metal), not a {base}
// refuses: coat-ior-not-1.5 = {id}: the clearcoat's IOR is fixed at 1.5 (f0 = 0.04); this coat's IOR relative to the
//   exterior is {coat_eta}
//
// models/builtin/08-gltf-clearcoat.glsl: `gltf-clearcoat`, the coat of glTF 2.0 (KHR_materials_clearcoat), with
// clearcoat = 1 and the clearcoat normal the surface's, over glTF's metal-rough base, as the specification computes
// it (the glTF-Sample-Viewer's pbr.frag @9dfbb82b computes the same for these two bases; earlier Viewers: +viewer):
//   clearcoat_fresnel = 0.04 + 0.96 (1 - |v.n|)^5                                     (clearcoat README, l. 140)
//   f = (1 - clearcoat_fresnel) material + clearcoat_fresnel D(a_c) Vis(a_c)         (l. 141-144)
// with D the GGX distribution and Vis the height-correlated Smith visibility of Appendix B (l. 3095-3132; the
// separable form before glTF PR #2541, commit 9c5e0d6d, 2026-01), alpha the roughness squared (gonio's `roughness`
// key is alpha itself). The clearcoat lobe has no Fresnel of its own. material:
//   a Lambertian base: baseColor / pi (metallic 0, KHR_materials_specular's specularFactor 0: no specular lobe)
//   a conductor: (F0 + (1 - F0) (1 - |v.h|)^5) D(a_b) Vis(a_b)   (metallic 1, baseColor = F0; l. 3195-3196)
// The variant +viewer (CONVENTION_COAT_FRESNEL_VH), the Sample Viewer's punctual lights: its clearcoat term is
// BRDF_specularGGX(clearcoatF0, 1, alpha_c, 1, ...) = F_Schlick(0.04, 1, v.h) Vis D, and the layer blending
// color = base (1 - clearcoatFactor F_Schlick(0.04, 1, n.v)) + f_clearcoat; the same D and height-correlated Vis, and
// the same base (specularWeight 0 leaves the Lambertian c_diff = baseColor). The Viewer's clearcoatF0 is the coat
// IOR's ((1.5 - 1) / (1.5 + 1))^2 = 0.04 (material_info.glsl @4e1b2ec takes info.f0 after the metal-rough step,
// which makes it baseColor over a metal; later versions take it from the IOR: gonio takes 0.04). Later Viewers
// compute the specification's mix (the `gltf-clearcoat` formula), so the variant is the reading the glTF threads
// discuss (glTF PR #1775, #2392; Sample Viewer #546), not today's Viewer.
// The mapping from the stack (docs/MODELS.md): clearcoatRoughness = sqrt(alpha_coat); a Lambertian base's albedo
// as baseColor; a conductor's F0 its normal-incidence reflectance ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) with n and k
// relative to the exterior (a metal's colour as an artist measures it in air), roughness = sqrt(alpha_base).
// Multiple scattering: the GGX lobes are single-scattering, as Appendix B writes them; the specification "suggest[s]
// to incorporate multiple scattering whenever possible" (specification/2.0/Specification.adoc @77b44be7, "Microfacet
// Surfaces": Heitz 2016, Kulla & Conty 2017 or Turquin 2019) without prescribing a scheme, which this model, the
// appendix's, leaves out.
#ifndef GONIO_MODEL_GLTF_CLEARCOAT_GLSL
#define GONIO_MODEL_GLTF_CLEARCOAT_GLSL
#include "models/common.glsl"
#include "models/production.glsl"   // metal_f0

// Appendix B's microfacet specular_brdf = Vis D, with l and v above the surface: D (l. 3095) and the
// height-correlated Vis (l. 3098-3125), written as the specification writes them but for D's denominator
// (n.h)^2 (alpha^2 - 1) + 1, taken as (1 - (n.h)^2) + (n.h)^2 alpha^2 with 1 - (n.h)^2 = h.x^2 + h.y^2: the same
// number, without the cancellation that makes the literal form wrong in float near the peak of a narrow lobe (at
// alpha 1e-4, the smooth coat's stand-in, a directional albedo of 11.6 instead of 1)
GONIO_INLINE float gltf_specular_brdf(vec3 l, vec3 v, float alpha) {
    if (l.z <= 0.0f || v.z <= 0.0f) return 0.0f;
    const vec3 h = normalize(l + v);
    const float a2 = alpha * alpha, nh = h.z, nl = l.z, nv = v.z;
    const float d = (h.x * h.x + h.y * h.y) + nh * nh * a2;
    const float D = a2 / (PI * d * d);
    const float vis = 1.0f / (2.0f * (nv * sqrt(a2 + (1.0f - a2) * nl * nl) + nl * sqrt(a2 + (1.0f - a2) * nv * nv)));
    return D * vis;
}

// glTF's Schlick Fresnel, f0 + (1 - f0) (1 - c)^5
GONIO_INLINE vec3 gltf_schlick(vec3 f0, float c) {
    const float x = 1.0f - c, x2 = x * x;
    return f0 + (vec3(1.0f) - f0) * (x2 * x2 * x);
}

// The base as glTF's metal-rough material: a Lambertian with specular off, a metal of F0 the conductor's
// normal-incidence reflectance in the exterior (p.base_c0, p.base_c1 are n and k relative to the coat), or a
// dielectric (metallic 0, specular on): Appendix B's dielectric_brdf = fresnel_mix(ior, diffuse, specular_brdf) =
// (1 - F) baseColor / pi + F specular_brdf, F Schlick at |v.h| with f0 = ((ior - 1) / (ior + 1))^2
// (KHR_materials_ior: ior = n_base / n_exterior, the clearcoat leaving it alone); the diffuse is TERM_DIFFUSE
GONIO_INLINE vec3 gltf_base(CoatParams p, uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
    if (p.base_kind == KIND_LAMBERTIAN) return (terms & TERM_BASE) != 0u ? p.base_c0 * INV_PI : vec3(0.0f);
    const vec3 h = normalize(l + v);
    if (p.base_kind == KIND_DIELECTRIC) {
        const float ior = p.eta * p.base_eta, f0 = (ior - 1.0f) * (ior - 1.0f) / ((ior + 1.0f) * (ior + 1.0f));
        const float fr = gltf_schlick(vec3(f0), min(abs(dot(v, h)), 1.0f)).x;
        vec3 b = vec3(0.0f);
        if ((terms & TERM_BASE) != 0u) b += vec3(fr * gltf_specular_brdf(l, v, p.alpha1));
        if ((terms & TERM_DIFFUSE) != 0u) b += (1.0f - fr) * layer_albedo(model_layer(2u)) * INV_PI;
        return b;
    }
    if (p.base_kind != KIND_CONDUCTOR) return vec3(model_nan());
    if ((terms & TERM_BASE) == 0u) return vec3(0.0f);
    const vec3 f0 = conductor_normal_reflectance(p.base_c0 * p.eta, p.base_c1 * p.eta);
    return gltf_schlick(f0, abs(dot(v, h))) * gltf_specular_brdf(l, v, p.alpha1);
}

GONIO_INLINE vec3 model_gltf_clearcoat(CoatParams p, uint terms, vec3 l, vec3 v) {
    const float fc = gltf_schlick(vec3(0.04f), abs(v.z)).x;   // clearcoat_fresnel, at n.v
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u && l.z > 0.0f && v.z > 0.0f) {
        // the coat lobe's weight: clearcoat_fresnel (the specification), or Schlick at v.h (the Sample Viewer's)
        const float fl = (model_convention() & CONVENTION_COAT_FRESNEL_VH) != 0u
                             ? gltf_schlick(vec3(0.04f), min(abs(dot(v, normalize(l + v))), 1.0f)).x
                             : fc;
        f += vec3(fl * gltf_specular_brdf(l, v, p.alpha0));
    }
    if ((terms & (TERM_BASE | TERM_DIFFUSE)) != 0u) f += (1.0f - fc) * gltf_base(p, terms, l, v);
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void gltf_clearcoat_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);              // clearcoat
    artist_value(a, sqrt(p.alpha0));    // clearcoatRoughness
    if (p.base_kind == KIND_CONDUCTOR) {
        artist_value(a, 1.0f);            // metallic
        artist_value(a, metal_f0(p));     // baseColor
        artist_value(a, sqrt(p.alpha1));  // roughness
    } else if (p.base_kind == KIND_DIELECTRIC) {
        artist_value(a, 0.0f);                  // metallic
        artist_value(a, diffuse);               // baseColor
        artist_value(a, p.eta * p.base_eta);    // ior (KHR_materials_ior), relative to the exterior
        artist_value(a, 1.0f);                  // specularFactor
        artist_value(a, vec3(1.0f));            // specularColorFactor
        artist_value(a, sqrt(p.alpha1));        // roughness
    } else {
        artist_value(a, 0.0f);        // metallic
        artist_value(a, p.base_c0);   // baseColor
        artist_value(a, 0.0f);        // specularFactor
    }
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) gltf_clearcoat_artist_parameters(p, diffuse, a)
#endif
