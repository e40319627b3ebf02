// gonio-model: openpbr-adobe
// citation: adobe/openpbr-bsdf @a29da969 (Adobe's OpenPBR BSDF, Apache-2.0): impl/openpbr_bsdf.h (prepare:
//   roughening, darkening L421-541), impl/openpbr_coating_lobe.h, impl/openpbr_diffuse_lobe.h,
//   impl/openpbr_microfacet_multiple_scattering_lobes.h, impl/openpbr_lobe_utils.h, the energy tables of
//   impl/data/*.h and their lookups (impl/openpbr_microfacet_multiple_scattering_data.h), openpbr_settings.h
//   OPENPBR_RECIPROCAL_COAT_AND_FUZZ 0 (its default); coat_weight 1, coat_darkening 1, fuzz_weight 0
// family: production
// summary: f_coat + Delta T(v) T(l) (1 - E_c(v)) f_base(l, v; r'): OpenPBR as Adobe's code computes it: the coat's
//   GGX lobe with separable Smith G, the base scaled by 1 - E_c from the viewer's side only, tinted along both
//   directions, darkened with the average Fresnel in K_s, roughened by 1 - 1/eta_c instead of 2; a diffuse base with
//   its energy-compensation factor, a metal in F82-tint with its multiple-scattering lobe
// stacks: one dielectric coat over a Lambertian or conductor base
// mapping: coat_weight 1, coat_darkening 1, coat_ior = n_coat / n_exterior, coat_roughness = sqrt(alpha_coat),
//   coat_color = exp(-2 tau), fuzz_weight 0; a Lambertian of albedo A: base_metalness 0, base_color A, base_weight 1,
//   specular_weight 0, specular_roughness 0, base_diffuse_roughness 0; a conductor: base_metalness 1, base_color F0 =
//   ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), specular_color min(1, F(1/7) / F_S(1/7)) (the F82 tint), specular_weight 1,
//   n and k relative to the exterior, specular_roughness = sqrt(alpha_base)
// artist-parameters: coat-over-lambertian = coat_weight, coat_darkening, coat_ior, coat_roughness,
//   coat_color (colour), fuzz_weight, base_metalness, base_color (colour), base_weight, specular_weight,
//   specular_roughness, base_diffuse_roughness
// artist-parameters: coat-over-conductor = coat_weight, coat_darkening, coat_ior, coat_roughness, coat_color (colour),
//   fuzz_weight, base_metalness, base_color (colour), specular_color (colour), specular_weight, specular_roughness
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: no
// energy-conserving: no (the base is scaled by 1 - E_c(v), the coat's albedo seen from v only: "energy-conserving
//   instead of reciprocal", adobe/openpbr-bsdf PR #30)
// variant: +reciprocal = convention reciprocal-coat: with OPENPBR_RECIPROCAL_COAT_AND_FUZZ 1 (openpbr_settings.h,
//   the code before PR #30): the base scaled by (1 - E_c(v)) (1 - E_c(l)), every factor then symmetric in l and v but
//   the cap 1 / mu_l of the metal's multiple-scattering lobe, which binds only near the horizon where its tables'
//   average IMA is near 0 (r' from 0.04 to about 0.07)
// variant-reciprocal: +reciprocal = yes
// variant-energy-note: +reciprocal = not by construction (Delta and the diffuse's compensation are Adobe's
//   approximations); no excess found on the hard cases (largest 0.9998)
// plan: coat
// table: adobe-energy 98
// tables: adobe-energy
// refuses: scattering-medium = {id} has no scattering medium ({layer}): OpenPBR's coat medium is purely absorbing
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian base (its diffuse with specular_weight 0) or a
//   conductor (its metal), not a {base}
// refuses: not-two-layers = {id} is one coat over one base here; this stack has {layers} layers
//
// models/builtin/14-openpbr-adobe.glsl: `openpbr-adobe`, OpenPBR as adobe/openpbr-bsdf evaluates it (openpbr_eval
// returns f |cos theta_l|; this is that over mu_l), for v the view direction openpbr_prepare takes, l the light:
//   f = f_coat(l, v) + Delta T(mu_v) T(mu_l) (1 - E_c(mu_v)) [1 - E_c(mu_l): +reciprocal] f_base(l, v)
// f_coat: GGX of alpha_c = r_c^2 (clamped at 1e-6 in D and G only), the separable Smith G1(v) G1(l) ("non-correlated",
// openpbr_lobe_utils.h), the exact dielectric Fresnel of eta_c = coat_ior / exterior_ior at |v.h|; no compensation.
// E_c(mu): the coat's albedo, exact Fresnel F(mu, eta_c) when r_c = 0, else 1 - OD(eta_c, alpha_c, mu), the "opaque
// dielectric energy complement" table (single-scatter reflection, separable G). T(mu) = sqrt(coat_color)^(1 / mu^t),
// mu^t = sqrt(1 - (1 - mu^2) / eta_c^2) (the cosine refracted into the coat), coat_color = exp(-2 tau) (the mapping),
// so T = exp(-tau / mu^t). Roughening: r' = (min(1, r^4 + X r_c^4))^(1/4), X = 1 - 1/eta_c (1 - eta_c below 1), r the
// specular_roughness. Darkening: Delta = (1 - K) / (1 - E_b K), K = mix(K_s, K_r, rough_b), K_s = avgF(eta_c) (the
// average Fresnel, its TODO: "use directional Fresnel"), K_r = 1 - (1 - avgF(eta_c)) / eta_c^2, avgF Kulla & Conty's
// fit (eta = 1 on the branch below 1: 0.00267).
// A Lambertian (base_metalness 0, specular_weight 0): the specular's IOR relative to the coat is then exactly 1, so
// its lobe vanishes; specularity s0 = avgF(1) = 0.00267, rough_b = mix(1, r', s0), E_b = mix(A, 1, s0); the diffuse
// lobe (EON at base_diffuse_roughness 0: A / pi (1 + 1e-7 A)) keeps its compensation factor
//   OD(1, alpha'_s, mu_v) OD(1, alpha'_s, mu_l) / max(ODA(1, alpha'_s), 1e-12), alpha'_s = r'^2,
// the tables at IOR 1 (node 16, tabulated at 1.0001), about 1 except near grazing at small r'.
// A metal (base_metalness 1, specular_weight 1): F82-tint saturated (f0 = base_color, its b from specular_color) at
// |v.h| in GGX of alpha'_s = r'^2 with separable G, plus its multiple-scattering lobe avgF82^2 min(IM(alpha'_s, mu_v)
// IM(alpha'_s, mu_l) / max(IMA(alpha'_s), 1e-12), 1 / mu_l) / pi (zero for r' < 0.04); E_b = avgF82 = saturate(F0 +
// (1 - F0) / 21 - b / 126), rough_b = r'. The coat's IOR leaves the metal's Fresnel alone.
// The tables (impl/data/*.h, 32 nodes an axis: IOR, roughness r = sqrt(alpha), mu) are recomputed by gonio's
// quadrature at Adobe's nodes (adobe_tables below, on the host; compared with the published values in
// tests/test_production_tables.cpp) and read as its trilinear lookups read them: their interpolation in IOR and
// roughness done once per stack, along mu here (STACK_TABLE_ADOBE_*).
#ifndef GONIO_MODEL_OPENPBR_ADOBE_GLSL
#define GONIO_MODEL_OPENPBR_ADOBE_GLSL
#include "models/common.glsl"
#include "models/production.glsl"

// The tables' nodes (openpbr_microfacet_multiple_scattering_data.h; the tabulated values at the ends, read back from
// the published tables: IOR 1.0001 at index 16, 1 / 1.0001 at 15, mu = 0.001 at index 0): index i of the IOR axis is
// the IOR 1 + (i - 16) / 10 from 16 to 31, 1 / (1 + (15 - i) / 10) from 0 to 15; j of the roughness axis r = j / 31
// (alpha = r^2); k of the cosine axis mu = k / 31
GONIO_INLINE float adobe_ior_node(uint i) {
    if (i == 16u) return 1.0001f;
    if (i == 15u) return 1.0f / 1.0001f;
    return i >= 16u ? 1.0f + float(i - 16u) / 10.0f : 1.0f / (1.0f + float(15u - i) / 10.0f);
}
GONIO_INLINE float adobe_mu_node(uint k) { return k == 0u ? 0.001f : float(k) / 31.0f; }

// The set this file declares (`table: adobe-energy`): the tables as the trilinear lookups read them for this stack's
// IOR and roughnesses, along the ADOBE_TABLE_NODES cosine nodes (adobe_mu_node); each part that has an average ends
// with it
const uint ADOBE_TABLE_NODES = 32u;
const uint STACK_TABLE_ADOBE_COAT = STACK_TABLE_ADOBE_ENERGY;   // E_c(mu) = 1 - OD(eta_c, alpha_c, mu)
// OD(1, alpha'_s, mu), ODA(1, alpha'_s); IM(alpha'_s, mu), IMA(alpha'_s)
const uint STACK_TABLE_ADOBE_DIFFUSE = STACK_TABLE_ADOBE_COAT + ADOBE_TABLE_NODES;
const uint STACK_TABLE_ADOBE_METAL = STACK_TABLE_ADOBE_DIFFUSE + ADOBE_TABLE_NODES + 1u;
#ifdef __cplusplus
static_assert(STACK_TABLE_ADOBE_METAL + ADOBE_TABLE_NODES + 1u ==
                  STACK_TABLE_ADOBE_ENERGY + STACK_TABLE_ADOBE_ENERGY_FLOATS,
              "the set's `table:` size");
#endif
// The exact index of an IOR on the IOR axis (openpbr_ior_to_exact_index), and of alpha on the roughness axis
GONIO_INLINE float adobe_ior_index(float ior) {
    if (ior < 1.0f) return 15.0f - (1.0f / ior - 1.0f) * (1.0f / 1.5f) * 15.0f;
    return 16.0f + (ior - 1.0f) * (1.0f / 1.5f) * 15.0f;
}
GONIO_INLINE float adobe_alpha_index(float alpha) { return sqrt(alpha) * 31.0f; }
// The opaque-dielectric tables beyond IOR 2.5 (or below 1 / 2.5): value (1 - (f0(ior) - F0max) / (1 - F0max))
// (openpbr_extrapolate_table_value_beyond_ior_max_if_needed), f0 = ((ior - 1) / (ior + 1))^2
GONIO_INLINE float adobe_ior_extrapolation(float ior) {
    if (!(ior > 2.5f || ior < 1.0f / 2.5f)) return 1.0f;
    const float f0_max = (1.5f / 3.5f) * (1.5f / 3.5f), f0 = (ior - 1.0f) * (ior - 1.0f) / ((ior + 1.0f) * (ior + 1.0f));
    return 1.0f - (f0 - f0_max) / (1.0f - f0_max);
}

// Adobe's average Fresnel (openpbr_average_fresnel): Kulla & Conty's fit, eta = 1 on the branch below 1
GONIO_INLINE float adobe_average_fresnel(float eta) {
    return eta > 1.0f ? kulla_conty_average_fresnel_above_1(eta) : kulla_conty_average_fresnel_below_1(eta);
}

// A smooth interface's roughness (the models' stand-in MODEL_MIN_ALPHA) as 0, what it is in the stack; the specular
// roughness of the mapping: sqrt(alpha_base) for a metal, 0 for a Lambertian
GONIO_INLINE float adobe_alpha(float a) { return a > MODEL_MIN_ALPHA ? a : 0.0f; }
GONIO_INLINE float adobe_specular_roughness(CoatParams p) {
    return p.base_kind == KIND_CONDUCTOR ? sqrt(adobe_alpha(p.alpha1)) : 0.0f;
}
// The roughened specular roughness r' = (min(1, r^4 + X r_c^4))^(1/4), X = 1 - 1/eta_c (1 - eta_c below 1)
GONIO_INLINE float adobe_roughened(CoatParams p) {
    const float r = adobe_specular_roughness(p), rc2 = adobe_alpha(p.alpha0);
    const float x = 1.0f - (p.eta >= 1.0f ? 1.0f / p.eta : p.eta);
    return sqrt(sqrt(min(1.0f, r * r * r * r + x * rc2 * rc2)));
}
// The plan's base roughness (GONIO_MODEL_BASE_ALPHA, models/all.glsl): alpha'_s = r'^2, D and G's clamp 1e-6 raised to
// the models' MODEL_MIN_ALPHA
GONIO_INLINE float openpbr_adobe_base_alpha(CoatParams p) {
    const float r = adobe_roughened(p);
    return max(MODEL_MIN_ALPHA, r * r);
}
#define GONIO_MODEL_BASE_ALPHA(p) openpbr_adobe_base_alpha(p)

// E_c(mu): exact Fresnel for a smooth coat, else the per-stack set (1 - OD interpolated); 0 at or below the horizon
GONIO_INLINE float adobe_coat_albedo(CoatParams p, float mu) {
    if (mu <= 0.0f) return 0.0f;
    if (adobe_alpha(p.alpha0) == 0.0f) return fresnel_dielectric(mu, p.eta);
    return model_stack_table_at(STACK_TABLE_ADOBE_COAT, ADOBE_TABLE_NODES, mu);
}
// T(mu) = sqrt(coat_color)^(1 / mu^t) = exp(-tau / mu^t) (1 in a channel that does not absorb; 0 where mu^t = 0 in
// one that does: pow's and safe_pow's limits)
GONIO_INLINE vec3 adobe_coat_tint(CoatParams p, float mu) {
    return coat_transmittance(p.tau, sqrt(max(0.0f, 1.0f - (1.0f - mu * mu) / (p.eta * p.eta))));
}

GONIO_INLINE vec3 model_openpbr_adobe(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    const vec3 h = normalize(l + v);
    if ((terms & TERM_TOP) != 0u)
        f += vec3(fresnel_dielectric(abs(dot(v, h)), p.eta) * ggx_D(h, p.alpha0) * ggx_G2_separable(l, v, p.alpha0) /
                  (4.0f * l.z * v.z));
    if ((terms & TERM_BASE) == 0u) return f;
    const float r = adobe_roughened(p), alpha_s = openpbr_adobe_base_alpha(p);
    const float k_s = adobe_average_fresnel(p.eta), k_r = 1.0f - (1.0f - k_s) / (p.eta * p.eta);
    vec3 base, e_b;
    float rough_b;
    if (p.base_kind == KIND_LAMBERTIAN) {
        const float s0 = adobe_average_fresnel(1.0f);
        rough_b = mix(1.0f, r, s0);
        e_b = mix(p.base_c0, vec3(1.0f), s0);
        const float oda = max(model_stack_table(STACK_TABLE_ADOBE_DIFFUSE + ADOBE_TABLE_NODES), 1e-12f);
        base = p.base_c0 * INV_PI * (vec3(1.0f) + 1e-7f * p.base_c0) *
               (model_stack_table_at(STACK_TABLE_ADOBE_DIFFUSE, ADOBE_TABLE_NODES, v.z) *
                model_stack_table_at(STACK_TABLE_ADOBE_DIFFUSE, ADOBE_TABLE_NODES, l.z) / oda);
    } else if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p), tint = metal_f82_tint(p, f0);
        const vec3 f_avg = clamp(f82_tint_average(f0, tint), vec3(0.0f), vec3(1.0f));
        rough_b = r;
        e_b = f_avg;
        base = f82_tint_saturated(f0, tint, abs(dot(v, h))) *
               (ggx_D(h, alpha_s) * ggx_G2_separable(l, v, alpha_s) / (4.0f * l.z * v.z));
        if (r * r >= 0.04f * 0.04f) {
            const float ima = max(model_stack_table(STACK_TABLE_ADOBE_METAL + ADOBE_TABLE_NODES), 1e-12f);
            const float im = model_stack_table_at(STACK_TABLE_ADOBE_METAL, ADOBE_TABLE_NODES, v.z) *
                             model_stack_table_at(STACK_TABLE_ADOBE_METAL, ADOBE_TABLE_NODES, l.z) / ima;
            base += f_avg * f_avg * (min(im, 1.0f / l.z) * INV_PI);
        }
    } else {
        return vec3(model_nan());
    }
    const float k = mix(k_s, k_r, rough_b);
    const vec3 darkening = vec3(1.0f - k) / (vec3(1.0f) - e_b * k);
    float scale = 1.0f - adobe_coat_albedo(p, v.z);
    if ((model_convention() & CONVENTION_RECIPROCAL_COAT) != 0u) scale *= 1.0f - adobe_coat_albedo(p, l.z);
    return f + darkening * adobe_coat_tint(p, v.z) * adobe_coat_tint(p, l.z) * scale * base;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void openpbr_adobe_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);                 // coat_weight
    artist_value(a, 1.0f);                 // coat_darkening
    artist_value(a, p.eta);                // coat_ior
    artist_value(a, sqrt(p.alpha0));       // coat_roughness
    artist_value(a, exp(-2.0f * p.tau));   // coat_color
    artist_value(a, 0.0f);                 // fuzz_weight
    if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p);
        artist_value(a, 1.0f);                     // base_metalness
        artist_value(a, f0);                       // base_color
        artist_value(a, metal_f82_tint(p, f0));    // specular_color
        artist_value(a, 1.0f);                     // specular_weight
        artist_value(a, sqrt(p.alpha1));           // specular_roughness
    } else {
        artist_value(a, 0.0f);        // base_metalness
        artist_value(a, p.base_c0);   // base_color
        artist_value(a, 1.0f);        // base_weight
        artist_value(a, 0.0f);        // specular_weight
        artist_value(a, 0.0f);        // specular_roughness
        artist_value(a, 0.0f);        // base_diffuse_roughness
    }
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) openpbr_adobe_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// adobe-energy on the host (model_twin.h). Adobe's tables at its nodes (adobe_ior_node, roughness j / 31,
// adobe_mu_node), what impl/data/*.h tabulate, by gonio's quadrature (separable G): the complements 1 - E kept in
// [0, 1] as the published unorm16 values are (the quadrature's 1e-5 above 1 at j = 1)
GONIO_INLINE float adobe_opaque_dielectric_complement(uint i, uint j, uint k) {   // OD[i][j][k]
    const float r = float(j) / 31.0f;
    return max(0.0f, 1.0f - table_interface_sums(adobe_ior_node(i), r * r, adobe_mu_node(k), FGD_SEPARABLE).fgd.x);
}
GONIO_INLINE float adobe_opaque_dielectric_average_complement(uint i, uint j) {   // ODA[i][j]
    const float r = float(j) / 31.0f;
    return float(max(0.0, 1.0 - table_cosine_average(TABLE_MEAN_FGD, adobe_ior_node(i), r * r, FGD_SEPARABLE)));
}
GONIO_INLINE float adobe_ideal_metal_complement(uint j, uint k) {   // IM[j][k]
    const float r = float(j) / 31.0f;
    return max(0.0f, 1.0f - table_interface_sums(1.5f, r * r, adobe_mu_node(k), FGD_SEPARABLE).lobe);
}
GONIO_INLINE float adobe_ideal_metal_average_complement(uint j) {   // IMA[j]
    const float r = float(j) / 31.0f;
    return float(max(0.0, 1.0 - table_cosine_average(TABLE_MEAN_LOBE, 1.5f, r * r, FGD_SEPARABLE)));
}
// A table of the base's at node j of the roughness axis: OD at IOR 1 (index 16, exactly a node) or IM, at cosine
// node k; k = ADOBE_TABLE_NODES: ODA or IMA
GONIO_INLINE float adobe_base_table(bool metal, uint j, uint k) {
    if (k == ADOBE_TABLE_NODES)
        return metal ? adobe_ideal_metal_average_complement(j) : adobe_opaque_dielectric_average_complement(16u, j);
    return metal ? adobe_ideal_metal_complement(j, k) : adobe_opaque_dielectric_complement(16u, j, k);
}
// The stack's coat albedo E_c(mu_k) = 1 - OD(eta_c, alpha_c, mu_k) (trilinear in IOR and roughness, with the
// extrapolation beyond IOR 2.5), and the base's OD(1, alpha'_s, mu_k) and ODA, or IM(alpha'_s, mu_k) and IMA,
// along alpha'_s = r'^2
GONIO_INLINE void adobe_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_ADOBE_ENERGY) == 0u || table_stack_shape(s) != TABLE_SHAPE_TWO_LAYER_OPAQUE) return;
    const CoatParams p = coat_params(s.layers[0], s.layers[1]);
    const TableAxisCell ior = table_axis_cell(adobe_ior_index(p.eta), ADOBE_TABLE_NODES);
    const TableAxisCell rc = table_axis_cell(adobe_alpha_index(adobe_alpha(p.alpha0)), ADOBE_TABLE_NODES);
    const float extrapolation = adobe_ior_extrapolation(p.eta);
    for (uint k = 0u; k < ADOBE_TABLE_NODES; ++k) {
        const float od_ll = adobe_opaque_dielectric_complement(ior.lo, rc.lo, k);
        const float lo = od_ll + (adobe_opaque_dielectric_complement(ior.hi, rc.lo, k) - od_ll) * ior.t;
        float hi = lo;
        if (rc.t > 0.0f) {
            const float od_lh = adobe_opaque_dielectric_complement(ior.lo, rc.hi, k);
            hi = od_lh + (adobe_opaque_dielectric_complement(ior.hi, rc.hi, k) - od_lh) * ior.t;
        }
        model_stack_table_store(STACK_TABLE_ADOBE_COAT + k, 1.0f - extrapolation * (lo + (hi - lo) * rc.t));
    }
    const float r = adobe_roughened(p);
    const TableAxisCell rs = table_axis_cell(adobe_alpha_index(r * r), ADOBE_TABLE_NODES);
    const bool metal = p.base_kind == KIND_CONDUCTOR;
    const uint offset = metal ? STACK_TABLE_ADOBE_METAL : STACK_TABLE_ADOBE_DIFFUSE;
    for (uint k = 0u; k <= ADOBE_TABLE_NODES; ++k) {
        const float lo = adobe_base_table(metal, rs.lo, k);
        model_stack_table_store(offset + k,
                                lo + (rs.t > 0.0f ? (adobe_base_table(metal, rs.hi, k) - lo) * rs.t : 0.0f));
    }
}
#define GONIO_MODEL_TABLES(s, sets) adobe_tables(s, sets)
#endif
#endif
