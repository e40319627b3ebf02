// gonio-model: openpbr
// citation: OpenPBR Surface v1.1.1 (AcademySoftwareFoundation/OpenPBR index.html @f8d6d94: "Layering" eq.
//   non-reciprocal-albedo-scaling-with-T, "Microfacet model" (its energy compensation), "Coat" (Darkening,
//   View-dependent absorption, Roughening), "Metal" (F82-tint), footnote avg_fresnel), coat_weight 1 and coat_darkening 1
//   (the defaults of a present coat); the compensation as its reference graph applies it (MaterialX @4177b2cb
//   mx_ggx_energy_compensation, after Turquin 2019)
// family: production
// summary: f_coat + T_coat^(1/mu_l + 1/mu_v) (1 - E_coat(v)) Delta f_base(l, v; r'_B): albedo scaling with the
//   coat's view-dependent absorption, the darkening Delta = (1 - K) / (1 - E_b K) and the base roughened to
//   min(1, r_B^4 + 2 r_C^4)^(1/4); a metal base as F82-tint; the base's GGX lobes (metal, dielectric base) with Turquin's
//   energy compensation 1 + F_avg (1 - E_ss(mu_v)) / E_ss(mu_v), E_ss gonio's quadrature
// stacks: one dielectric coat (relative IOR in [1/3, 3]) over a Lambertian, a conductor, or a dielectric interface over a
//   Lambertian (its glossy-diffuse base)
// mapping: coat_weight 1, coat_darkening 1, coat_ior = n_coat / n_exterior, coat_roughness = sqrt(alpha_coat),
//   coat_color = exp(-2 tau); a Lambertian of albedo A: base_metalness 0, base_color A, specular_weight 0,
//   specular_roughness 0; a conductor:
//   base_metalness 1, base_color F0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), specular_color min(1, F(1/7) /
//   F_Schlick(1/7)), n and k relative to the exterior, specular_roughness = sqrt(alpha_base); a dielectric interface
//   over a Lambertian of albedo A: base_metalness 0, base_color A, specular_weight 1, specular_ior = n_base /
//   n_exterior, specular_roughness = sqrt(alpha_base)
// artist-parameters: coat-over-lambertian = coat_weight, coat_darkening, coat_ior, coat_roughness,
//   coat_color (colour), base_metalness, base_color (colour), specular_weight, specular_roughness
// artist-parameters: coat-over-conductor = coat_weight, coat_darkening, coat_ior, coat_roughness, coat_color (colour),
//   base_metalness, base_color (colour), specular_color (colour), specular_roughness
// artist-parameters: coat-over-dielectric-over-lambertian = coat_weight, coat_darkening, coat_ior, coat_roughness,
//   coat_color (colour), base_metalness, base_color (colour), specular_weight, specular_ior, specular_roughness
// represents: coat-over-lambertian, coat-over-conductor, coat-over-dielectric-over-lambertian
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - E_coat(v), the coat's albedo seen from v, not from l)
// parameter: coat_darkening default 1 range [0, 1] -- OpenPBR's coat_darkening delta: the base scaled by
//   lerp(1, Delta, delta) (coat_weight 1); 0 takes the darkening out (the reference MaterialX graph, +materialx,
//   keeps it whole)
// variant: +dev1.2 = convention darkening-t2: with dev_1.2's darkening (OpenPBR @475bd90, branch dev_1.2,
//   eq. general_darkening_formula_with_absorption): Delta = (1 - K) / (1 - K E_b T^2), T^2 = coat_color, the coat's
//   absorption in the base's inter-reflections
// variant-energy-note: +dev1.2 = the base is scaled by 1 - E_coat(v), as openpbr's; it runs only under an absorbing
//   coat (elsewhere it is openpbr, which exceeds 1 as it does: 1.683 at 89.9 degrees on stacks/hard/ior-3-metal), where
//   the hard cases measured at most 1.629 (the same stack, its coat absorbing)
// variant: +materialx = convention materialx-graph: as OpenPBR's reference MaterialX graph computes it (MaterialX
//   @4177b2cb libraries/bxdf/open_pbr_surface.mtlx, its pbrlib GLSL): K = 1 - (1 - F0_coat) / eta^2 for every base,
//   E_b = base_color; coat_color once, not T^(1/mu_l^t + 1/mu_v^t); the coat a dielectric_bsdf layered over the base
//   (Turquin's compensation, throughput 1 - E_mx(v) comp); the metal a compensated generalized_schlick_bsdf; a
//   diffuse base under its dielectric_bsdf of specular_weight 0 (IOR 1), whose throughput still takes B comp
// variant-energy-note: +materialx = the base is scaled by MaterialX's throughput 1 - E_mx(v) comp(v), seen from v;
//   1.771 at 89.9 degrees on stacks/hard/dense-exterior, a coat of IOR 0.5 relative to the exterior, where its
//   K = 1 - (1 - F0) / eta^2 is -2.56 and the darkening brightens the base
// variant: +pr261 = convention roughening-pr261: with OpenPBR PR #261's roughening (open, head 2026-03-31: "fit to
//   Monte Carlo simulations"): alpha'_B = 0.85 tanh(sqrt((eta alpha_B)^2 + (B alpha_C)^2) / 0.85), B = 1.05 (eta - 1)
//   sqrt(1 + eta^2) / eta
// variant: +separable = convention separable-g: with the separable Smith G1(l) G1(v) in every GGX lobe (the coat's, a
//   metal's, a dielectric base's) and in the albedos E_coat and E_s they give: the form adobe/openpbr-bsdf takes; the
//   specification's "well-known form [Heitz 2014]" names neither, its reference graph takes the height-correlated G2
// variant: +numerator = convention darkening-numerator: with the numerator of the darkening corrected as OpenPBR
//   #269 and the comment of 2025-09-04 on PR #253 state it (the SIGGRAPH write-up's AddCoat): Delta =
//   ((1 - E_F) / eta^2) / (1 - E_b K), K = lerp(K_s, K_r, r_b) left in the denominator; the same as openpbr's over a
//   Lambertian (r_b = 1: 1 - K_r = (1 - E_F) / eta^2), different where the base is smooth
// variant: +single = convention single-scattering-lobes: the base's GGX lobes (metal, dielectric base) as the
//   specification's eq. microfacet_brdf_ss prints them, single-scattering, without the energy compensation its
//   "Microfacet model" section asks an implementation for ("should ideally account for this")
// plan: coat
// table: openpbr-base-albedo 130
// table: openpbr-separable 130
// table: openpbr-lobe-albedo 196
// tables: coat-albedo, openpbr-base-albedo, openpbr-separable, openpbr-lobe-albedo
// refuses: scattering-medium = {id} has no scattering medium ({layer}): OpenPBR's coat medium V_coat is purely
//   absorbing
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian base (OpenPBR's diffuse with specular_weight 0)
//   or a conductor (its metal), not a {base}
// refuses: not-coat-over-base = {id} is one coat over one base here (a Lambertian, a conductor, or a dielectric
//   interface over a Lambertian); this stack has {layers} layers
// refuses: absorbing-base-medium = {id}'s dielectric base has no medium between its specular interface and its
//   diffuse ({layer})
// refuses: coat-ior-beyond-3 = {id}: the darkening's hemispherical Fresnel albedo is the specification's fit, valid
//   for a relative coat IOR in [1/3, 3]; this coat's IOR relative to the exterior is {coat_eta}
//
// models/builtin/09-openpbr.glsl: `openpbr`, the coat of OpenPBR Surface v1.1.1 as its specification computes it, at
// coat_weight C = 1 and coat_darkening delta = 1 (so lerp(1, Delta, C delta) = Delta):
//   f = f_coat(l, v) + T^(1/mu_l^t + 1/mu_v^t) (1 - E_coat(v)) Delta f_base(l, v)
// f_coat: the coat's GGX dielectric reflection with the exact Fresnel of the coat IOR eta_c = n_coat / n_exterior
// and the height-correlated Smith G2 (the specification's "well-known form [Heitz 2014]"; its reference graph,
// reference/open_pbr_surface.mtlx, evaluates MaterialX's dielectric_bsdf, whose mx_ggx_smith_G2 is height-correlated;
// adobe/openpbr-bsdf uses the separable form). E_coat(v): that lobe's directional albedo (gonio's table,
// host/models/stack_tables.cpp). mu^t: the cosines refracted into the coat, mu^t = sqrt(1 - (1 - mu^2) / eta_c^2).
// Darkening: Delta = (1 - K) / (1 - E_b K) per channel, K = lerp(K_s, K_r, r_b), K_s = F(mu_v, eta_c),
// K_r = 1 - (1 - E_F(eta_c)) / eta_c^2 with E_F d'Eon's fit the specification prints. A Lambertian base: r_b = r_d =
// lerp(1, r, xi_s F_s) = 1 (specular_weight xi_s = 0), so K = K_r, and E_b its albedo. A metal: r_b = r_m =
// specular_roughness, E_b its F0 (its Fresnel at normal incidence: the specification leaves the base's
// normal-incidence albedo to the implementation; a smooth metal's exactly). Roughening (coat_weight 1):
// r'_B = min(1, r_B^4 + 2 r_C^4)^(1/4), i.e. alpha'_B = sqrt(min(1, alpha_B^2 + 2 alpha_C^2)). The base is
// evaluated at the unrefracted directions (the specification's reduction to a mixture of lobes): base_color / pi for
// a Lambertian, and the metal's GGX lobe F82(|l.h|) D G2 / (4 mu_l mu_v) C(mu_v) with
//   F82(mu) = F_S(mu) - mu (1 - mu)^6 / (mu_b (1 - mu_b)^6) (F_S(mu_b) - specular_color F_S(mu_b)), mu_b = 1/7,
//   F_S(mu) = F0 + (1 - F0) (1 - mu)^5.
// Energy compensation ("Microfacet model": the single-scattering lobe "should ideally account for" the light that
// scatters more than once between microfacets; +single leaves it out): each base lobe times Turquin's
//   C(mu_v) = 1 + F_avg (1 - E_ss(mu_v)) / E_ss(mu_v),
// the form of the reference graph (mx_ggx_energy_compensation at n.v), with E_ss(mu) the lobe's directional albedo at
// F = 1 (its alpha'_B and G) by gonio's quadrature (the set openpbr-lobe-albedo, not MaterialX's rational fit) and
// F_avg = 2 int F(mu) mu dmu of the lobe's own Fresnel: F82-tint's F0 + (1 - F0) / 21 - b / 126 for a metal (the
// graph: F0 + (1 - F0) / 21), E_F(eta_s) = 2 int F(mu, eta_s) mu dmu for a dielectric base (gonio's 24-point
// Gauss-Legendre of the exact Fresnel, per stack: eta_s may exceed the [1, 3] of d'Eon's fit). With F = 1 the lobe's albedo is then 1 at every
// mu_v. The coat's lobe stays single-scattering, as adobe/openpbr-bsdf keeps it (the graph compensates it too).
// The mapping from the stack (docs/MODELS.md): coat_ior = eta_c; coat_roughness = sqrt(alpha_coat); coat_color =
// exp(-2 tau) (the square of the normal-incidence transmittance, so that T = exp(-tau) per crossing); a Lambertian
// base: base_metalness 0, base_color = albedo, specular_weight 0; a conductor: base_metalness 1, base_color = F0 =
// ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) and specular_color = min(1, F(1/7) / F_S(1/7)) (the F82 tint, F the
// conductor's exact Fresnel), n and k relative to the exterior (a metal's colour as an artist measures it in air;
// F82-tint gives no complex IOR for the coat to change), specular_roughness = sqrt(alpha_base).
#ifndef GONIO_MODEL_OPENPBR_GLSL
#define GONIO_MODEL_OPENPBR_GLSL
#include "models/common.glsl"
#include "models/materialx.glsl"
#include "models/production.glsl"

// E_F(eta) = 2 int_0^1 F(mu, eta) mu dmu by d'Eon 2021's fit (OpenPBR footnote avg_fresnel, "within 0.2% in
// [1, 3]"), and below 1 by E_F(eta) = 1 - eta^2 (1 - E_F(1 / eta))
GONIO_INLINE float openpbr_fresnel_albedo(float eta) {
    const float e = eta >= 1.0f ? eta : 1.0f / eta;
    const float ef = log((10893.0f * e - 1438.2f) / (-774.4f * e * e + 10212.0f * e + 1.0f));
    return eta >= 1.0f ? ef : 1.0f - eta * eta * (1.0f - ef);
}

// A smooth interface's roughness (the models' stand-in MODEL_MIN_ALPHA) as 0, what it is in the stack
GONIO_INLINE float openpbr_alpha(float a) { return a > MODEL_MIN_ALPHA ? a : 0.0f; }

// Roughening at coat_weight 1: r'_B = min(1, r_B^4 + 2 r_C^4)^(1/4), alpha = r^2 (main and dev_1.2); PR #261's
// alpha'_B = 0.85 tanh(sqrt((eta alpha_B)^2 + (B(eta) alpha_C)^2) / 0.85), B(eta) = 1.05 (eta - 1) sqrt(1 + eta^2) / eta
// (CONVENTION_ROUGHENING_PR261). It applies to "the microfacet BSDF lobes of the underlying base substrate (metal and
// dielectric)". The plan's base roughness (GONIO_MODEL_BASE_ALPHA, models/all.glsl)
GONIO_INLINE float openpbr_roughened_alpha(CoatParams p, bool pr261) {
    const float ab = openpbr_alpha(p.alpha1), ac = openpbr_alpha(p.alpha0);
    if (pr261) {
        const float b = 1.05f * (p.eta - 1.0f) * sqrt(1.0f + p.eta * p.eta) / p.eta;
        const float raw = sqrt(p.eta * ab * p.eta * ab + b * ac * b * ac);
        return max(MODEL_MIN_ALPHA, 0.85f * float(tanh(raw / 0.85f)));
    }
    return max(MODEL_MIN_ALPHA, sqrt(min(1.0f, ab * ab + 2.0f * ac * ac)));
}
GONIO_INLINE float openpbr_base_alpha(CoatParams p) {
    return openpbr_roughened_alpha(p, (model_convention() & CONVENTION_ROUGHENING_PR261) != 0u);
}

// A dielectric base's specular IOR relative to the coat at coat_weight 1, eta_s = n_b / n_c, with the TIR fix (after
// Kutz 2021: n_c / n_b where the coat is the denser): max(n_b, n_c) / min(n_b, n_c)
GONIO_INLINE float openpbr_specular_eta(CoatParams p) { return p.base_eta >= 1.0f ? p.base_eta : 1.0f / p.base_eta; }

// Smith's G in every GGX lobe: the height-correlated G2 (Heitz 2014 eq. 99, as the reference graph's
// mx_ggx_smith_G2), or the separable G1(l) G1(v) (Heitz 2014 eq. 98, adobe/openpbr-bsdf's; CONVENTION_SEPARABLE_G)
GONIO_INLINE bool openpbr_separable() { return (model_convention() & CONVENTION_SEPARABLE_G) != 0u; }
GONIO_INLINE float openpbr_G(vec3 l, vec3 v, float a) {
    return openpbr_separable() ? ggx_G2_separable(l, v, a) : ggx_G2(l, v, a);
}

// A dielectric interface's GGX reflection of relative IOR eta (the coat's, a dielectric base's): the exact Fresnel,
// D, and openpbr_G
GONIO_INLINE float openpbr_dielectric_lobe(vec3 l, vec3 v, float a, float eta) {
    const vec3 h = normalize(l + v);
    return fresnel_dielectric(dot(l, h), eta) * ggx_D(h, a) * openpbr_G(l, v, a) / (4.0f * l.z * v.z);
}

// The sets this file declares (`table:`), each COAT_ALBEDO_NODES values of mu: openpbr-base-albedo, a dielectric
// base's specular albedo E_s(mu) under the coat (three layers: OpenPBR's glossy-diffuse base, the lobe of eta_s at its
// roughened alpha'_B, G2) with the specification's roughening, then with PR #261's; openpbr-separable, E_coat(mu) and,
// three layers, the dielectric base's E_s(mu) (the specification's roughening), each with the separable Smith G;
// openpbr-lobe-albedo, the base lobe's E_ss(mu) at F = 1 (a metal or a dielectric base, its alpha'_B): G2 with the
// specification's roughening, G2 with PR #261's, the separable G with the specification's; then one value, a
// dielectric base's average Fresnel E_F(eta_s)
const uint STACK_TABLE_OPENPBR_BASE = STACK_TABLE_OPENPBR_BASE_ALBEDO;
const uint STACK_TABLE_OPENPBR_BASE_PR261 = STACK_TABLE_OPENPBR_BASE + COAT_ALBEDO_NODES;
const uint STACK_TABLE_OPENPBR_SEPARABLE_COAT = STACK_TABLE_OPENPBR_SEPARABLE;
const uint STACK_TABLE_OPENPBR_SEPARABLE_BASE = STACK_TABLE_OPENPBR_SEPARABLE_COAT + COAT_ALBEDO_NODES;
const uint STACK_TABLE_OPENPBR_LOBE = STACK_TABLE_OPENPBR_LOBE_ALBEDO;
const uint STACK_TABLE_OPENPBR_LOBE_PR261 = STACK_TABLE_OPENPBR_LOBE + COAT_ALBEDO_NODES;
const uint STACK_TABLE_OPENPBR_LOBE_SEPARABLE = STACK_TABLE_OPENPBR_LOBE_PR261 + COAT_ALBEDO_NODES;
const uint STACK_TABLE_OPENPBR_LOBE_FRESNEL = STACK_TABLE_OPENPBR_LOBE_SEPARABLE + COAT_ALBEDO_NODES;
#ifdef __cplusplus
static_assert(2u * COAT_ALBEDO_NODES == STACK_TABLE_OPENPBR_BASE_ALBEDO_FLOATS &&
                  2u * COAT_ALBEDO_NODES == STACK_TABLE_OPENPBR_SEPARABLE_FLOATS &&
                  3u * COAT_ALBEDO_NODES + 1u == STACK_TABLE_OPENPBR_LOBE_ALBEDO_FLOATS,
              "the sets' `table:` sizes");
#endif

// E_coat(mu): the coat lobe's directional albedo (tables: coat-albedo with G2, openpbr-separable's first set)
GONIO_INLINE float openpbr_coat_albedo(float mu) {
    return openpbr_separable() ? model_stack_table_at(STACK_TABLE_OPENPBR_SEPARABLE_COAT, COAT_ALBEDO_NODES, mu)
                               : model_stack_table_at(STACK_TABLE_COAT_ALBEDO, COAT_ALBEDO_NODES, mu);
}

// E_s(mu): the directional albedo of the dielectric base's specular lobe (F(eta_s), GGX of the roughened alpha'_B,
// openpbr_G) from its per-stack set (tables: openpbr-base-albedo, the specification's roughening and PR #261's;
// openpbr-separable's second set)
GONIO_INLINE float openpbr_specular_albedo(float mu) {
    const bool pr261 = (model_convention() & CONVENTION_ROUGHENING_PR261) != 0u;
    const uint set = openpbr_separable() ? STACK_TABLE_OPENPBR_SEPARABLE_BASE
                     : pr261             ? STACK_TABLE_OPENPBR_BASE_PR261
                                         : STACK_TABLE_OPENPBR_BASE;
    return model_stack_table_at(set, COAT_ALBEDO_NODES, mu);
}
#define GONIO_MODEL_BASE_ALPHA(p) openpbr_base_alpha(p)

// C(mu_v) = 1 + F_avg (1 - E_ss(mu_v)) / E_ss(mu_v), a base lobe's energy compensation (Turquin 2019, as
// mx_ggx_energy_compensation applies it), E_ss from openpbr-lobe-albedo for the roughening and G that run; 1 under
// +single. E_ss > 0 at every mu (the quadrature's limit at mu = 0 is finite and positive; 1 below MODEL_MIN_ALPHA)
GONIO_INLINE vec3 openpbr_energy_compensation(float mu_v, vec3 f_avg) {
    if ((model_convention() & CONVENTION_SINGLE_SCATTERING_LOBES) != 0u) return vec3(1.0f);
    const bool pr261 = (model_convention() & CONVENTION_ROUGHENING_PR261) != 0u;
    const uint set = openpbr_separable() ? STACK_TABLE_OPENPBR_LOBE_SEPARABLE
                     : pr261             ? STACK_TABLE_OPENPBR_LOBE_PR261
                                         : STACK_TABLE_OPENPBR_LOBE;
    const float e = model_stack_table_at(set, COAT_ALBEDO_NODES, mu_v);
    return vec3(1.0f) + f_avg * ((1.0f - e) / e);
}

// The darkening Delta = (1 - K) / (1 - E_b K) of the base seen through the coat from v (dev_1.2: E_b T^2 in the
// denominator, CONVENTION_DARKENING_T2)
// K = lerp(K_s, K_r, r_b): a Lambertian base r_b = r_d = 1 (specular_weight 0); a metal r_b = r_m = specular_roughness;
// a dielectric base r_b = r_d = lerp(1, specular_roughness, xi_s F_s), F_s = ((1 - eta_s) / (1 + eta_s))^2
// ("unmodulated_fresnel"), xi_s = specular_weight = 1
GONIO_INLINE vec3 openpbr_darkening(CoatParams p, vec3 e_b, float mu_v) {
    const float k_r = 1.0f - (1.0f - openpbr_fresnel_albedo(p.eta)) / (p.eta * p.eta);
    float k = k_r;   // a Lambertian base: r_b = 1
    if (p.base_kind == KIND_CONDUCTOR) k = mix(fresnel_dielectric(mu_v, p.eta), k_r, sqrt(openpbr_alpha(p.alpha1)));
    if (p.base_kind == KIND_DIELECTRIC) {
        const float eta_s = openpbr_specular_eta(p), f_s = (1.0f - eta_s) * (1.0f - eta_s) / ((1.0f + eta_s) * (1.0f + eta_s));
        k = mix(fresnel_dielectric(mu_v, p.eta), k_r, mix(1.0f, sqrt(openpbr_alpha(p.alpha1)), f_s));
    }
    // dev_1.2: the base's albedo in the inter-reflections is the one seen through the coat twice, E_b T^2
    const vec3 t2 = (model_convention() & CONVENTION_DARKENING_T2) != 0u ? exp(-2.0f * p.tau) : vec3(1.0f);
    // #269's numerator: the light that leaves the coat's inside for air, 1 - K_r, whatever the base's roughness
    const float numerator = (model_convention() & CONVENTION_DARKENING_NUMERATOR) != 0u ? 1.0f - k_r : 1.0f - k;
    return vec3(numerator) / (vec3(1.0f) - e_b * t2 * k);
}

// The reference MaterialX graph (CONVENTION_MATERIALX_GRAPH, MaterialX @4177b2cb open_pbr_surface.mtlx) at
// coat_weight 1, coat_darkening 1: layer(dielectric_bsdf(coat_ior, coat alpha), coat_color Delta base_substrate) with
// Delta = (1 - Kcoat) / (1 - Ebase Kcoat), Kcoat = 1 - (1 - F0(coat_ior)) / coat_ior^2, Ebase = base_color (the metal's
// base_color specular_weight); base_substrate: the metal's generalized_schlick_bsdf (color0 F0, color82 the tint,
// color90 1, exponent 5, Turquin-compensated), or layer(dielectric_bsdf(IOR 1 at specular_weight 0), oren_nayar of
// roughness 0 = albedo / pi), both at the roughened main roughness
GONIO_INLINE vec3 openpbr_materialx_graph(CoatParams p, uint terms, vec3 l, vec3 v) {
    const float nv = clamp(v.z, MX_FLOAT_EPS, 1.0f), vh = clamp(dot(v, normalize(l + v)), MX_FLOAT_EPS, 1.0f);
    const float ac = clamp(p.alpha0, MX_FLOAT_EPS, 1.0f), ab = clamp(openpbr_base_alpha(p), MX_FLOAT_EPS, 1.0f);
    const float f0c = mx_dielectric_f0(p.eta);
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u)
        f += vec3(fresnel_dielectric(vh, p.eta) * mx_ggx_lobe(l, v, ac) * mx_ggx_energy_compensation(nv, ac, vec3(f0c)).x);
    if ((terms & (TERM_BASE | TERM_DIFFUSE)) == 0u) return f;
    vec3 base = vec3(0.0f), e_b;
    if (p.base_kind == KIND_LAMBERTIAN) {
        if ((terms & TERM_BASE) != 0u) base = p.base_c0 * INV_PI * mx_dielectric_throughput(v.z, ab, 1.0f);
        e_b = p.base_c0;
    } else if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p);
        if ((terms & TERM_BASE) != 0u)
            base = mx_fresnel_f82(vh, f0, metal_f82_tint(p, f0)) * mx_ggx_energy_compensation(nv, ab, f0) *
                   mx_ggx_lobe(l, v, ab);
        e_b = f0;
    } else if (p.base_kind == KIND_DIELECTRIC) {
        // the glossy-diffuse base: layer(dielectric_bsdf(eta_s, alpha'_B), oren_nayar of roughness 0), E_b = base_color
        const float eta_s = openpbr_specular_eta(p);
        const vec3 a = layer_albedo(model_layer(2u));
        if ((terms & TERM_BASE) != 0u)
            base += vec3(fresnel_dielectric(vh, eta_s) * mx_ggx_lobe(l, v, ab) *
                         mx_ggx_energy_compensation(nv, ab, vec3(mx_dielectric_f0(eta_s))).x);
        if ((terms & TERM_DIFFUSE) != 0u) base += a * INV_PI * mx_dielectric_throughput(v.z, ab, eta_s);
        e_b = a;
    } else {
        return vec3(model_nan());
    }
    const float k = 1.0f - (1.0f - f0c) / (p.eta * p.eta);
    const vec3 darkening = vec3(1.0f - k) / (vec3(1.0f) - e_b * k);
    return f + mx_dielectric_throughput(v.z, ac, p.eta) * exp(-2.0f * p.tau) * darkening * base;
}

GONIO_INLINE vec3 model_openpbr(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if ((model_convention() & CONVENTION_MATERIALX_GRAPH) != 0u) return openpbr_materialx_graph(p, terms, l, v);
    if ((terms & TERM_TOP) != 0u) f += vec3(openpbr_dielectric_lobe(l, v, p.alpha0, p.eta));
    if ((terms & (TERM_BASE | TERM_DIFFUSE)) == 0u) return f;
    vec3 base = vec3(0.0f), e_b;
    if (p.base_kind == KIND_LAMBERTIAN) {
        if ((terms & TERM_BASE) != 0u) base = p.base_c0 * INV_PI;
        e_b = p.base_c0;
    } else if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p);
        const float a = openpbr_base_alpha(p);
        const vec3 h = normalize(l + v);
        const vec3 tint = metal_f82_tint(p, f0);
        if ((terms & TERM_BASE) != 0u)
            base = f82_tint(f0, tint, abs(dot(l, h))) * (ggx_D(h, a) * openpbr_G(l, v, a) / (4.0f * l.z * v.z)) *
                   openpbr_energy_compensation(v.z, f82_tint_average(f0, tint));
        e_b = f0;
    } else if (p.base_kind == KIND_DIELECTRIC) {
        // the glossy-diffuse base (specular_weight 1, base_metalness 0): f_spec + (1 - E_s(v)) base_color / pi, f_spec
        // the GGX dielectric reflection of eta_s at the roughened alpha'_B with the exact Fresnel and G2, compensated
        // (C_s, F_avg = E_F(eta_s) from the set), E_s(mu) = E_ss,F(mu) C_s(mu) its albedo; E_b its normal-incidence
        // albedo E_s(1) + (1 - E_s(1)) base_color (the slabs' albedos at normal incidence, "Darkening")
        const float eta_s = openpbr_specular_eta(p), a = openpbr_base_alpha(p);
        const float f_avg = model_stack_table(STACK_TABLE_OPENPBR_LOBE_FRESNEL);
        const vec3 albedo = layer_albedo(model_layer(2u));
        const float c_v = openpbr_energy_compensation(v.z, vec3(f_avg)).x;
        if ((terms & TERM_BASE) != 0u) base += vec3(openpbr_dielectric_lobe(l, v, a, eta_s) * c_v);
        if ((terms & TERM_DIFFUSE) != 0u) base += (1.0f - openpbr_specular_albedo(v.z) * c_v) * albedo * INV_PI;
        const float e_s = openpbr_specular_albedo(1.0f) * openpbr_energy_compensation(1.0f, vec3(f_avg)).x;
        e_b = vec3(e_s) + (1.0f - e_s) * albedo;
    } else {
        return vec3(model_nan());
    }
    const vec3 l1 = refract_into_coat(l, p.eta), v1 = refract_into_coat(v, p.eta);
    // the modulated darkening factor lerp(1, Delta, C delta) ("Darkening"), C = coat_weight = 1
    const vec3 darkening = mix(vec3(1.0f), openpbr_darkening(p, e_b, v.z), param_coat_darkening);
    return f + coat_attenuation(p.tau, l1, v1) * (1.0f - openpbr_coat_albedo(v.z)) * darkening * base;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void openpbr_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);                 // coat_weight
    artist_value(a, 1.0f);                 // coat_darkening
    artist_value(a, p.eta);                // coat_ior
    artist_value(a, sqrt(p.alpha0));       // coat_roughness
    artist_value(a, exp(-2.0f * p.tau));   // coat_color
    if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p);
        artist_value(a, 1.0f);                     // base_metalness
        artist_value(a, f0);                       // base_color
        artist_value(a, metal_f82_tint(p, f0));    // specular_color
        artist_value(a, sqrt(p.alpha1));           // specular_roughness
    } else if (p.base_kind == KIND_DIELECTRIC) {
        artist_value(a, 0.0f);                  // base_metalness
        artist_value(a, diffuse);               // base_color
        artist_value(a, 1.0f);                  // specular_weight
        artist_value(a, p.eta * p.base_eta);    // specular_ior, relative to the exterior
        artist_value(a, sqrt(p.alpha1));        // specular_roughness
    } else {
        artist_value(a, 0.0f);        // base_metalness
        artist_value(a, p.base_c0);   // base_color
        artist_value(a, 0.0f);        // specular_weight
        artist_value(a, 0.0f);        // specular_roughness
    }
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) openpbr_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// The sets this file declares, on the host (model_twin.h): by gonio's one quadrature of an interface's albedo; the
// base lobe's at F = 1 where the base is a conductor or a dielectric; the coat's (openpbr-separable's first) where the
// stack has a coat over an opaque or a dielectric base, the dielectric base's where it has one
GONIO_INLINE void openpbr_tables(StackGpu s, uint sets) {
    const uint shape = table_stack_shape(s);
    if (shape == TABLE_SHAPE_OTHER) return;
    const CoatParams p = coat_params(s.layers[0], s.layers[1]);
    if ((sets & STACK_TABLES_OPENPBR_LOBE_ALBEDO) != 0u &&
        (p.base_kind == KIND_CONDUCTOR || shape == TABLE_SHAPE_THREE_LAYER_DIELECTRIC_BASE)) {
        table_store_lobe_albedo(STACK_TABLE_OPENPBR_LOBE, openpbr_roughened_alpha(p, false), FGD_G2);
        table_store_lobe_albedo(STACK_TABLE_OPENPBR_LOBE_PR261, openpbr_roughened_alpha(p, true), FGD_G2);
        table_store_lobe_albedo(STACK_TABLE_OPENPBR_LOBE_SEPARABLE, openpbr_roughened_alpha(p, false), FGD_SEPARABLE);
        if (shape == TABLE_SHAPE_THREE_LAYER_DIELECTRIC_BASE)
            model_stack_table_store(STACK_TABLE_OPENPBR_LOBE_FRESNEL,
                                    float(table_cosine_average(TABLE_MEAN_FRESNEL, openpbr_specular_eta(p), 0.0f, FGD_G2)));
    }
    if ((sets & STACK_TABLES_OPENPBR_SEPARABLE) != 0u)
        table_store_interface_albedo(STACK_TABLE_OPENPBR_SEPARABLE_COAT, layer_eta(s.layers[0]),
                                     layer_alpha(s.layers[0]), FGD_SEPARABLE);
    if (shape != TABLE_SHAPE_THREE_LAYER_DIELECTRIC_BASE) return;
    if ((sets & STACK_TABLES_OPENPBR_BASE_ALBEDO) != 0u) {
        table_store_interface_albedo(STACK_TABLE_OPENPBR_BASE, openpbr_specular_eta(p),
                                     openpbr_roughened_alpha(p, false), FGD_G2);
        table_store_interface_albedo(STACK_TABLE_OPENPBR_BASE_PR261, openpbr_specular_eta(p),
                                     openpbr_roughened_alpha(p, true), FGD_G2);
    }
    if ((sets & STACK_TABLES_OPENPBR_SEPARABLE) != 0u)
        table_store_interface_albedo(STACK_TABLE_OPENPBR_SEPARABLE_BASE, openpbr_specular_eta(p),
                                     openpbr_roughened_alpha(p, false), FGD_SEPARABLE);
}
#define GONIO_MODEL_TABLES(s, sets) openpbr_tables(s, sets)
#endif
#endif
