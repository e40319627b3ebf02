// gonio-model: standard-surface
// citation: Autodesk Standard Surface 1.0 (Georgiev et al. 2019; Autodesk/standard-surface index.html @34b1d5bd:
//   "Coating", "Metal", "Layering"; reference/standard_surface.osl for the metal's artistic Fresnel), coat 1 and
//   coat_affect_color = coat_affect_roughness = 0 (their defaults)
// family: production
// summary: coat_brdf + coat_color (1 - reflectance(coat_brdf)) f_base: the coat's GGX lobe, and the base scaled by
//   the coat's directional albedo seen from v and tinted once by coat_color; no refraction, the coat IOR leaves the
//   base alone; a metal base in Gulbrandsen's artistic Fresnel
// stacks: one dielectric coat over a Lambertian, a conductor, or a dielectric interface over a Lambertian (its
//   specular layer over its diffuse)
// mapping: coat 1, coat_IOR = n_coat / n_exterior, coat_roughness = sqrt(alpha_coat), coat_color = exp(-2 tau),
//   coat_affect_color 0, coat_affect_roughness 0; a Lambertian of albedo A: base 1, base_color A, diffuse_roughness 0,
//   specular 0, metalness 0; a conductor: metalness 1, base_color r = F0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2),
//   specular_color g = (n_max(r) - n) / (n_max(r) - n_min(r)) (Gulbrandsen's edge tint), n and k relative to the
//   exterior, specular_roughness = sqrt(alpha_base); a dielectric interface over a Lambertian of albedo A: base 1,
//   base_color A, diffuse_roughness 0, metalness 0, specular 1, specular_color 1, specular_IOR = n_base / n_exterior,
//   specular_roughness = sqrt(alpha_base)
// artist-parameters: coat-over-lambertian = coat, coat_IOR, coat_roughness, coat_color (colour), coat_affect_color,
//   coat_affect_roughness, base, base_color (colour), diffuse_roughness, specular, metalness
// artist-parameters: coat-over-conductor = coat, coat_IOR, coat_roughness, coat_color (colour), coat_affect_color,
//   coat_affect_roughness, metalness, base_color (colour), specular_color (colour), specular_roughness
// artist-parameters: coat-over-dielectric-over-lambertian = coat, coat_IOR, coat_roughness, coat_color (colour),
//   coat_affect_color, coat_affect_roughness, base, base_color (colour), diffuse_roughness, metalness, specular,
//   specular_color (colour), specular_IOR, specular_roughness
// represents: coat-over-lambertian, coat-over-conductor, coat-over-dielectric-over-lambertian
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - E_coat(v), the coat's albedo seen from v, not from l: conserving
//   seen from the viewer, as the specification says, not from the light)
// variant: +osl = convention reflectance-fresnel: with the reference OSL's reflectance(), "the dielectric fresnel at
//   the surface normal" (reference/standard_surface.osl: 1 - F(n.v) clamped to [0, 1], not the coat's albedo)
// plan: coat
// table: standard-surface-base-albedo 65
// tables: coat-albedo, standard-surface-base-albedo
// refuses: scattering-medium = {id} has no scattering medium ({layer}): its coat_color is a tint, not a medium
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian base (its diffuse with specular 0) or a
//   conductor (its metal), not a {base}
// refuses: not-coat-over-base = {id} is one coat over one base here (a Lambertian, a conductor, or its specular
//   layer over its diffuse); this stack has {layers} layers
// refuses: absorbing-base-medium = {id}'s specular layer lies on its diffuse, with no medium between ({layer})
//
// models/builtin/11-standard-surface.glsl: `standard-surface`, the coat of Autodesk Standard Surface 1.0 as its
// specification computes it ("Coating", coat = 1):
//   coat_layer = coat_brdf(l, v) + coat_color (1 - reflectance(coat_brdf)) f_base(l, v)
// coat_brdf: the GGX dielectric reflection of coat_IOR with alpha = coat_roughness^2 (reference OSL: params.
// coat_roughness = sqr(coat_roughness)), the exact Fresnel, and the height-correlated Smith G2 (the specification
// names none; its MaterialX graph, reference/standard_surface.mtlx, evaluates dielectric_bsdf, whose mx_ggx_smith_G2
// is height-correlated). reflectance(coat_brdf): "their Fresnel-governed hemispherical-directional reflectance (a.k.a.
// directional albedo)" ("Layering"), seen from the viewer: E_coat(v), gonio's table (host/models/stack_tables.cpp).
// The coat is "infinitely thin ... passed directly to the underlying layer without refraction": the base is
// evaluated at l and v, and the coat IOR does not change its Fresnel. coat_color tints the light from below once.
// The base: a Lambertian base_color / pi (diffuse_roughness 0: Oren-Nayar is Lambert; specular 0 leaves no
// specular lobe); a metal as reference/standard_surface.osl computes it: ArtisticToConductorFresnel(base_color,
// specular_color) gives n = lerp(n_max, n_min, g), k = sqrt(max(0, ((n + 1)^2 r - (n - 1)^2) / (1 - r))) with r
// clamped to [0, 0.99], then the conductor's exact Fresnel in a GGX lobe of alpha = specular_roughness^2. For the
// mapped (r, g) this gives back the stack's n and k (in the exterior) wherever F0 <= 0.99; above, r's clamp makes the
// metal darker, as it makes the authors'.
// The variant +osl: reference/standard_surface.osl's reflectance(), the dielectric Fresnel at the normal,
// F(n.v, coat_IOR), in place of the albedo ("TODO: use correct microfacet reflectance").
// Multiple scattering: every GGX lobe (the coat's, the metal's, the specular's) is single-scattering, as the
// specification and its OSL write them; neither mentions compensating the energy lost between microfacets (a rough
// metal here reflects the single-scattering albedo: 10-17% below the microsurface's own light at alpha 0.3, 34-69%
// at alpha 1 for gold and silver, docs/STUDIES.md "A rough metal's multiple scattering").
#ifndef GONIO_MODEL_STANDARD_SURFACE_GLSL
#define GONIO_MODEL_STANDARD_SURFACE_GLSL
#include "models/common.glsl"
#include "models/production.glsl"   // metal_f0

// Gulbrandsen's bounds on n for a reflectivity r: n_min = (1 - r) / (1 + r), n_max = (1 + sqrt r) / (1 - sqrt r)
GONIO_INLINE vec3 standard_surface_n_min(vec3 r) { return (vec3(1.0f) - r) / (vec3(1.0f) + r); }
GONIO_INLINE vec3 standard_surface_n_max(vec3 r) { return (vec3(1.0f) + sqrt(r)) / (vec3(1.0f) - sqrt(r)); }

// Standard Surface's metal Fresnel (reference/standard_surface.osl ArtisticToConductorFresnel, Gulbrandsen 2014) at
// the artistic parameters of the conductor (n, k) in the exterior: reflectivity r = F0 (base_color) and the edge tint
// g = (n_max(r) - n) / (n_max(r) - n_min(r)) (specular_color), from which the OSL takes r clamped to [0, 0.99],
// n = lerp(n_max, n_min, g) and k = sqrt(max(0, ((n + 1)^2 r - (n - 1)^2) / (1 - r)))
GONIO_INLINE vec3 standard_surface_metal_fresnel(float mu, vec3 n_ext, vec3 k_ext) {
    // (n_max = n_min = 1 only at F0 = 0, where n is 1 whatever g; F0 below 1 by 1e-6 keeps n_max finite)
    const vec3 f0 = min(conductor_normal_reflectance(n_ext, k_ext), vec3(1.0f - 1e-6f));
    const vec3 g = (standard_surface_n_max(f0) - n_ext) /
                   max(standard_surface_n_max(f0) - standard_surface_n_min(f0), vec3(1e-7f));
    const vec3 r = clamp(f0, vec3(0.0f), vec3(0.99f));
    const vec3 n = mix(standard_surface_n_max(r), standard_surface_n_min(r), g);
    const vec3 k = sqrt(max(vec3(0.0f), ((n + 1.0f) * (n + 1.0f) * r - (n - 1.0f) * (n - 1.0f)) / (vec3(1.0f) - r)));
    return fresnel_conductor(mu, n, k);
}

// 1 - reflectance(coat_brdf) seen from v: 1 - E_coat(v) (the specification), or 1 - F(n.v) clamped to [0, 1] (the
// reference OSL, CONVENTION_REFLECTANCE_FRESNEL)
GONIO_INLINE float standard_surface_coat_pass(CoatParams p, float mu_v) {
    if ((model_convention() & CONVENTION_REFLECTANCE_FRESNEL) != 0u)
        return clamp(1.0f - fresnel_dielectric(mu_v, p.eta), 0.0f, 1.0f);
    return 1.0f - model_stack_table_at(STACK_TABLE_COAT_ALBEDO, COAT_ALBEDO_NODES, mu_v);
}

GONIO_INLINE vec3 model_standard_surface(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if ((terms & TERM_TOP) != 0u) f += vec3(top_reflection(l, v, p.alpha0, p.eta));
    if ((terms & (TERM_BASE | TERM_DIFFUSE)) == 0u) return f;
    vec3 base = vec3(0.0f);
    if (p.base_kind == KIND_LAMBERTIAN) {
        if ((terms & TERM_BASE) != 0u) base = p.base_c0 * INV_PI;
    } else if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 h = normalize(l + v);
        if ((terms & TERM_BASE) != 0u)
            base = standard_surface_metal_fresnel(min(abs(dot(l, h)), 1.0f), p.base_c0 * p.eta, p.base_c1 * p.eta) *
                   (ggx_D(h, p.alpha1) * ggx_G2(l, v, p.alpha1) / (4.0f * l.z * v.z));
    } else if (p.base_kind == KIND_DIELECTRIC) {
        // the specular layer over the diffuse ("Specular", "Layering"): specular_brdf + (1 - reflectance(specular_brdf))
        // base_color / pi, the specular a GGX dielectric reflection of specular_IOR (the base's IOR relative to the
        // exterior: the coat leaves it alone) at its own roughness; reflectance its directional albedo E_spec(v)
        // (tables: standard-surface-base-albedo), or F(n.v, specular_IOR) for the OSL reference (+osl)
        const float eta_b = p.eta * p.base_eta;
        if ((terms & TERM_BASE) != 0u) base += vec3(top_reflection(l, v, p.alpha1, eta_b));
        if ((terms & TERM_DIFFUSE) != 0u) {
            const float pass =
                (model_convention() & CONVENTION_REFLECTANCE_FRESNEL) != 0u
                    ? clamp(1.0f - fresnel_dielectric(v.z, eta_b), 0.0f, 1.0f)
                    : 1.0f - model_stack_table_at(STACK_TABLE_STANDARD_SURFACE_BASE_ALBEDO, COAT_ALBEDO_NODES, v.z);
            base += pass * layer_albedo(model_layer(2u)) * INV_PI;
        }
    } else {
        return vec3(model_nan());
    }
    const vec3 coat_color = exp(-2.0f * p.tau);
    return f + coat_color * standard_surface_coat_pass(p, v.z) * base;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void standard_surface_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);                 // coat
    artist_value(a, p.eta);                // coat_IOR
    artist_value(a, sqrt(p.alpha0));       // coat_roughness
    artist_value(a, exp(-2.0f * p.tau));   // coat_color
    artist_value(a, 0.0f);                 // coat_affect_color
    artist_value(a, 0.0f);                 // coat_affect_roughness
    if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p), n = p.base_c0 * p.eta;   // n relative to the exterior
        const vec3 lo = standard_surface_n_min(f0), hi = standard_surface_n_max(f0);
        artist_value(a, 1.0f);                    // metalness
        artist_value(a, f0);                      // base_color
        artist_value(a, (hi - n) / (hi - lo));    // specular_color: Gulbrandsen's edge tint
        artist_value(a, sqrt(p.alpha1));          // specular_roughness
    } else if (p.base_kind == KIND_DIELECTRIC) {
        artist_value(a, 1.0f);                  // base
        artist_value(a, diffuse);               // base_color
        artist_value(a, 0.0f);                  // diffuse_roughness
        artist_value(a, 0.0f);                  // metalness
        artist_value(a, 1.0f);                  // specular
        artist_value(a, vec3(1.0f));            // specular_color
        artist_value(a, p.eta * p.base_eta);    // specular_IOR, relative to the exterior
        artist_value(a, sqrt(p.alpha1));        // specular_roughness
    } else {
        artist_value(a, 1.0f);        // base
        artist_value(a, p.base_c0);   // base_color
        artist_value(a, 0.0f);        // diffuse_roughness
        artist_value(a, 0.0f);        // specular
        artist_value(a, 0.0f);        // metalness
    }
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) standard_surface_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// standard-surface-base-albedo, on the host (model_twin.h): three layers, the specular layer's E_spec(mu) (the base
// interface's IOR relative to the exterior, its own roughness: the coat changes neither; G2) at COAT_ALBEDO_NODES
// nodes of mu, by gonio's one quadrature of an interface's albedo
static_assert(COAT_ALBEDO_NODES == STACK_TABLE_STANDARD_SURFACE_BASE_ALBEDO_FLOATS, "the set's `table:` size");
GONIO_INLINE void standard_surface_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_STANDARD_SURFACE_BASE_ALBEDO) == 0u ||
        table_stack_shape(s) != TABLE_SHAPE_THREE_LAYER_DIELECTRIC_BASE)
        return;
    const CoatParams p = coat_params(s.layers[0], s.layers[1]);
    table_store_interface_albedo(STACK_TABLE_STANDARD_SURFACE_BASE_ALBEDO, p.eta * p.base_eta, layer_alpha(s.layers[1]),
                                 FGD_G2);
}
#define GONIO_MODEL_TABLES(s, sets) standard_surface_tables(s, sets)
#endif
#endif
