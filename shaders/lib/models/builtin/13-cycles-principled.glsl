// gonio-model: cycles-principled
// citation: Blender Cycles Principled BSDF v2, as Blender 4.5 and 5.0 compute it (blender/cycles v5.0.0 @2eba4102:
//   src/kernel/svm/closure.h svm_node_closure_bsdf (coat, metal, diffuse), src/kernel/closure/bsdf_microfacet.h
//   (microfacet_ggx_preserve_energy, bsdf_microfacet_estimate_albedo), bsdf_util.h (closure_layering_weight,
//   fresnel_dielectric_Fss, fresnel_f82), the tables of src/scene/shader.tables as src/app/cycles_precompute.cpp
//   makes them), Coat Weight 1, the Multiscatter GGX distribution (its default)
// family: production
// summary: K_c(v) f_coat + L_c(v) tint^(1/mu_v^t) f_base: the coat's GGX lobe with Cycles' energy compensation, the
//   layers below it scaled once from the viewer's side, by 1 - the coat's estimated albedo (a table lookup) and by
//   the coat tint along the view direction refracted into the coat; no refraction, darkening or roughening of the base
// stacks: one dielectric coat (relative IOR at least 1) over a Lambertian or conductor base
// mapping: Coat Weight 1, Coat IOR = n_coat / n_exterior, Coat Roughness = sqrt(alpha_coat), Coat Tint = exp(-2 tau);
//   a Lambertian of albedo A: Metallic 0, Base Color A, Specular IOR Level 0, Diffuse Roughness 0; a conductor:
//   Metallic 1, Base Color F0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2), Specular Tint min(1, F(1/7) / F_S(1/7)) (the
//   F82 tint), n and k relative to the exterior, Roughness = sqrt(alpha_base)
// artist-parameters: coat-over-lambertian = Coat Weight, Coat IOR, Coat Roughness, Coat Tint (colour), Metallic,
//   Base Color (colour), Specular IOR Level, Diffuse Roughness
// artist-parameters: coat-over-conductor = Coat Weight, Coat IOR, Coat Roughness, Coat Tint (colour), Metallic,
//   Base Color (colour), Specular Tint (colour), Roughness
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: no
// energy-conserving: no (the layers below the coat are scaled by 1 - its albedo estimated from the viewer's side,
//   and tinted along the view direction only)
// variant: +4.4 = convention cycles-4.4: as Blender 4.0 to 4.4 compute the coat (blender/cycles v4.4.0 @f81bf6e4,
//   before Blender's fix #129306 "Principled coat doesn't pass furnace test"): no energy compensation on the coat
//   lobe, and the layers below scaled by 1 - F(mu_v, eta_c), the smooth coat's Fresnel at the view direction
// plan: coat
// table: cycles-energy 82
// tables: cycles-energy
// refuses: scattering-medium = {id} has no scattering medium ({layer}): its Coat Tint is a colour, not a medium
// refuses: transmissive = {id} models reflection only (a BRDF) here; this stack is transmissive (its last layer is a
//   dielectric)
// refuses: base-not-lambertian-or-conductor = {id} takes a Lambertian base (its diffuse with Specular IOR Level 0)
//   or a conductor (its metal), not a {base}
// refuses: not-two-layers = {id} is one coat over one base here; this stack has {layers} layers
// refuses: coat-ior-below-1 = {id}: Cycles clamps the Coat IOR to at least 1; this coat's IOR relative to the
//   exterior is {coat_eta}
//
// models/builtin/13-cycles-principled.glsl: `cycles-principled`, the coat of Blender Cycles' Principled BSDF as
// closure.h builds its closures (Coat Weight 1, Sheen 0, Transmission 0, Subsurface 0, no thin film). Cycles' value
// is the sum over the closures of weight x eval / mu_l (eval returns f cos theta_l); with v = sd->wi (towards the
// viewer), l the light:
//   f = K_c(mu_v) f_coat(l, v) + L_c(mu_v) tau_c(mu_v) f_base(l, v)
// f_coat: GGX of alpha_c = r_c^2 (bsdf_microfacet_ggx_setup), the exact dielectric Fresnel of the Coat IOR at v.h,
// and the height-correlated Smith G2 = 1 / (1 + Lambda(v) + Lambda(l)) (bsdf_microfacet_eval): the reference's.
// K_c: microfacet_ggx_preserve_energy with Fss = fresnel_dielectric_Fss(eta_c) (Kulla & Conty's fit): energy_scale
// 1 / E and the closure weight times the darkening (1 + F_ms (1 - E) / E) E, so
//   K_c = 1 + F_ms (1 - E) / E,   F_ms = F_ss E_avg / (1 - F_ss (1 - E_avg)),   E = ggx_E(r_c, mu_v), E_avg = ggx_Eavg(r_c).
// L_c: closure_layering_weight(albedo, weight) = weight saturate(1 - max_channel(albedo / weight)), albedo the coat
// closure's weight times bsdf_microfacet_estimate_albedo: (E + F_ms (1 - E)) (F0 + (1 - F0) s(r_c, mu_v, z_c)), F0 =
// ((eta_c - 1) / (eta_c + 1))^2, z_c = sqrt((eta_c - 1) / (eta_c + 1)), s Cycles' ggx_gen_schlick_ior_s table.
// tau_c: the Coat Tint along the view direction refracted into the coat, tint^(1 / mu_v^t), mu_v^t =
// sqrt(1 - (1 - mu_v^2) / eta_c^2), applied once to every layer below (closure.h: "tint is normalized to perpendicular
// incidence"). The base: a Lambertian Base Color / pi (Specular IOR Level 0 sets the specular's IOR to 1, which
// creates no specular closure; Diffuse Roughness 0 is Lambert); a metal (Metallic 1): the F82-tint Fresnel
// fresnel_f82 (saturated) at v.h with f0 = Base Color and b from the Specular Tint (fresnel_f82tint_B), GGX of
// alpha = Roughness^2, G2, and Multiscatter GGX's compensation 1 + F_ms (1 - E_m) / E_m with F_ss =
// fresnel_f82_Fss(f0, b) per channel, E_m = ggx_E(r, mu_v), E_avg = ggx_Eavg(r). Neither the coat's IOR nor its
// roughness changes the base. The tables (ggx_E 32 x 32 over roughness and mu, ggx_Eavg 32, ggx_gen_schlick_ior_s
// 16^3 over roughness, mu and z) are recomputed by gonio's quadrature at Cycles' nodes (host/models/stack_tables.cpp,
// compared with the published values in tests/test_models.cpp) and read as its lookup_table_read_2D / 3D read them:
// linear in each axis, here along mu from the per-stack sets (kernel_interface.glsl STACK_TABLE_CYCLES_*).
// The mapping (docs/MODELS.md): the Coat Tint is the coat's colour at normal incidence, the light's two passes:
// exp(-2 tau); the metal's Base Color and Specular Tint as OpenPBR's F82-tint metal takes them.
#ifndef GONIO_MODEL_CYCLES_PRINCIPLED_GLSL
#define GONIO_MODEL_CYCLES_PRINCIPLED_GLSL
#include "models/common.glsl"
#include "models/production.glsl"

// Cycles' table nodes (cycles_precompute.cpp): ggx_E and ggx_Eavg at roughness clamp(i / 31, 1e-4, 1) and mu =
// clamp(j / 31, 1e-4, 1); ggx_gen_schlick_ior_s at roughness clamp(i / 15, 1e-4, 1), mu = clamp(j / 15, 1e-4, 1) and
// z = clamp(k / 15, 1e-4, 0.99), the IOR (1 + z^2) / (1 - z^2) (z = F0^(1/4))
GONIO_INLINE float cycles_table_node(uint i, uint nodes, float hi) {
    return clamp(float(i) / float(nodes - 1u), 1e-4f, hi);
}

// The set this file declares (`table: cycles-energy`): the tables as lookup_table_read_2D / 3D read them for this
// stack's coat and base: ggx_E along its CYCLES_E_NODES nodes mu = j / 31 (j = 0 at mu = 1e-4) then ggx_Eavg, and
// ggx_gen_schlick_ior_s along its CYCLES_S_NODES nodes mu = j / 15
const uint CYCLES_E_NODES = 32u;
const uint CYCLES_S_NODES = 16u;
const uint STACK_TABLE_CYCLES_COAT_E = STACK_TABLE_CYCLES_ENERGY;   // ggx_E(r_c, mu), ggx_Eavg(r_c)
const uint STACK_TABLE_CYCLES_COAT_S = STACK_TABLE_CYCLES_COAT_E + CYCLES_E_NODES + 1u;   // s(r_c, mu, z_c)
const uint STACK_TABLE_CYCLES_BASE_E = STACK_TABLE_CYCLES_COAT_S + CYCLES_S_NODES;   // ggx_E(r_b, mu), ggx_Eavg(r_b)
#ifdef __cplusplus
static_assert(STACK_TABLE_CYCLES_BASE_E + CYCLES_E_NODES + 1u ==
                  STACK_TABLE_CYCLES_ENERGY + STACK_TABLE_CYCLES_ENERGY_FLOATS,
              "the set's `table:` size");
#endif

// Fresnel_dielectric_Fss(eta) (bsdf_util.h): Kulla & Conty's fit, the branch above 1 at eta = 1
GONIO_INLINE float cycles_fss(float eta) {
    return eta < 1.0f ? kulla_conty_average_fresnel_below_1(eta) : kulla_conty_average_fresnel_above_1(eta);
}

// The compensation 1 + F_ms (1 - E) / E of a GGX closure (microfacet_ggx_preserve_energy), from the per-stack set at
// `offset` (ggx_E along mu, then ggx_Eavg) and F_ss
GONIO_INLINE vec3 cycles_energy_compensation(uint offset, float mu_v, vec3 fss) {
    const float e = model_stack_table_at(offset, CYCLES_E_NODES, mu_v);
    const float e_avg = model_stack_table(offset + CYCLES_E_NODES);
    if (all(equal(fss, vec3(1.0f)))) return vec3(1.0f / e);   // no darkening: the energy scale 1 / E alone
    const vec3 fms = fss * e_avg / (vec3(1.0f) - fss * (1.0f - e_avg));
    return vec3(1.0f) + fms * ((1.0f - e) / e);
}

GONIO_INLINE bool cycles_coat_4_4() { return (model_convention() & CONVENTION_CYCLES_4_4) != 0u; }

// The coat closure's albedo as closure_layering_weight takes it (its weight times bsdf_microfacet_estimate_albedo),
// seen from v: the darkening E + F_ms (1 - E) times F0 + (1 - F0) s(r_c, mu_v, z_c); Blender 4.4: F(mu_v, eta_c)
GONIO_INLINE float cycles_coat_albedo(CoatParams p, float mu_v) {
    if (cycles_coat_4_4()) return fresnel_dielectric(mu_v, p.eta);
    if (!(p.eta > 1.0f)) return 0.0f;   // estimate_albedo: an IOR of 1 reflects nothing (F = 0)
    const float fss = cycles_fss(p.eta);
    const float e = model_stack_table_at(STACK_TABLE_CYCLES_COAT_E, CYCLES_E_NODES, mu_v);
    const float e_avg = model_stack_table(STACK_TABLE_CYCLES_COAT_E + CYCLES_E_NODES);
    const float fms = fss * e_avg / (1.0f - fss * (1.0f - e_avg));
    const float f0 = (p.eta - 1.0f) * (p.eta - 1.0f) / ((p.eta + 1.0f) * (p.eta + 1.0f));
    const float s = model_stack_table_at(STACK_TABLE_CYCLES_COAT_S, CYCLES_S_NODES, mu_v);
    return (e + fms * (1.0f - e)) * (f0 + (1.0f - f0) * s);
}

// The Coat Tint along the view direction refracted into the coat, tint^(1 / mu_v^t), tint = exp(-2 tau) (the
// mapping): exp(-2 tau / mu_v^t); 1 where a channel does not absorb (Cycles skips a tint of 1)
GONIO_INLINE vec3 cycles_coat_tint(CoatParams p, float mu_v) {
    const float mu_t = sqrt(max(0.0f, 1.0f - (1.0f - mu_v * mu_v) / (p.eta * p.eta)));
    return coat_transmittance(2.0f * p.tau, mu_t);
}

GONIO_INLINE vec3 model_cycles_principled(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if ((terms & TERM_TOP) != 0u) {
        const float fss = cycles_fss(p.eta);
        const float k_c =
            cycles_coat_4_4() ? 1.0f : cycles_energy_compensation(STACK_TABLE_CYCLES_COAT_E, v.z, vec3(fss)).x;
        f += vec3(k_c * top_reflection(l, v, p.alpha0, p.eta));
    }
    if ((terms & TERM_BASE) == 0u) return f;
    vec3 base;
    if (p.base_kind == KIND_LAMBERTIAN) {
        base = p.base_c0 * INV_PI;
    } else if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p), tint = metal_f82_tint(p, f0);
        const vec3 h = normalize(l + v);
        base = f82_tint_saturated(f0, tint, dot(v, h)) * (ggx_D(h, p.alpha1) * ggx_G2(l, v, p.alpha1) / (4.0f * l.z * v.z)) *
               cycles_energy_compensation(STACK_TABLE_CYCLES_BASE_E, v.z, f82_tint_average(f0, tint));
    } else {
        return vec3(model_nan());
    }
    const float layering = clamp(1.0f - cycles_coat_albedo(p, v.z), 0.0f, 1.0f);
    return f + layering * cycles_coat_tint(p, v.z) * base;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order)
GONIO_INLINE void cycles_principled_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, 1.0f);                 // Coat Weight
    artist_value(a, p.eta);                // Coat IOR
    artist_value(a, sqrt(p.alpha0));       // Coat Roughness
    artist_value(a, exp(-2.0f * p.tau));   // Coat Tint
    if (p.base_kind == KIND_CONDUCTOR) {
        const vec3 f0 = metal_f0(p);
        artist_value(a, 1.0f);                     // Metallic
        artist_value(a, f0);                       // Base Color
        artist_value(a, metal_f82_tint(p, f0));    // Specular Tint
        artist_value(a, sqrt(p.alpha1));           // Roughness
    } else {
        artist_value(a, 0.0f);        // Metallic
        artist_value(a, p.base_c0);   // Base Color
        artist_value(a, 0.0f);        // Specular IOR Level
        artist_value(a, 0.0f);        // Diffuse Roughness
    }
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) cycles_principled_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// cycles-energy on the host (model_twin.h): Cycles' tables at its nodes (cycles_table_node), what
// src/scene/shader.tables holds, by gonio's quadrature; then interpolated for the stack as Cycles' lookups are
GONIO_INLINE float cycles_ggx_e(uint i, uint j) {   // ggx_E at roughness node i, mu node j
    const float r = cycles_table_node(i, CYCLES_E_NODES, 1.0f);
    return table_interface_sums(1.5f, r * r, cycles_table_node(j, CYCLES_E_NODES, 1.0f), FGD_G2).lobe;
}
GONIO_INLINE float cycles_ggx_e_avg(uint i) {   // ggx_Eavg
    const float r = cycles_table_node(i, CYCLES_E_NODES, 1.0f);
    return float(table_cosine_average(TABLE_MEAN_LOBE, 1.5f, r * r, FGD_G2));
}
// ggx_gen_schlick_ior_s at (roughness i, mu j, z k): the mean over the visible normals of l of s(l.m) =
// saturate((F(l.m, ior) - F0) / (1 - F0)), 0 where v = reflect(l, m) is below the horizon (fgd_quadrature's
// visible-normal mode with the remapped Fresnel)
GONIO_INLINE float cycles_schlick_ior_s(uint i, uint j, uint k) {
    const float r = cycles_table_node(i, CYCLES_S_NODES, 1.0f), z = cycles_table_node(k, CYCLES_S_NODES, 0.99f);
    const float ior = (1.0f + z * z) / (1.0f - z * z);
    return table_interface_sums(ior, r * r, cycles_table_node(j, CYCLES_S_NODES, 1.0f),
                                FGD_VISIBLE_NORMALS | FGD_FRESNEL_REMAPPED)
        .fgd.x;
}
// ggx_E and ggx_Eavg at roughness alpha (a smooth interface's stand-in MODEL_MIN_ALPHA as 0), from `offset`
GONIO_INLINE void cycles_store_e_set(uint offset, float alpha) {
    const float a = alpha > MODEL_MIN_ALPHA ? alpha : 0.0f;
    const TableAxisCell r = table_axis_cell(clamp(sqrt(a), 0.0f, 1.0f) * float(CYCLES_E_NODES - 1u), CYCLES_E_NODES);
    for (uint j = 0u; j < CYCLES_E_NODES; ++j) {
        const float lo = cycles_ggx_e(r.lo, j);
        model_stack_table_store(offset + j, lo + (r.t > 0.0f ? (cycles_ggx_e(r.hi, j) - lo) * r.t : 0.0f));
    }
    const float lo = cycles_ggx_e_avg(r.lo);
    model_stack_table_store(offset + CYCLES_E_NODES,
                            lo + (r.t > 0.0f ? (cycles_ggx_e_avg(r.hi) - lo) * r.t : 0.0f));
}
// ggx_gen_schlick_ior_s at the coat's roughness and z = sqrt(|(eta - 1) / (eta + 1)|), bilinear in (r, z)
GONIO_INLINE void cycles_store_schlick_set(CoatParams p) {
    const float n = float(CYCLES_S_NODES - 1u), a = p.alpha0 > MODEL_MIN_ALPHA ? p.alpha0 : 0.0f;
    const TableAxisCell r = table_axis_cell(clamp(sqrt(a), 0.0f, 1.0f) * n, CYCLES_S_NODES);
    const TableAxisCell z =
        table_axis_cell(clamp(sqrt(abs((p.eta - 1.0f) / (p.eta + 1.0f))), 0.0f, 1.0f) * n, CYCLES_S_NODES);
    for (uint j = 0u; j < CYCLES_S_NODES; ++j) {
        const float s_ll = cycles_schlick_ior_s(r.lo, j, z.lo);
        const float lo = s_ll + (r.t > 0.0f ? (cycles_schlick_ior_s(r.hi, j, z.lo) - s_ll) * r.t : 0.0f);
        float hi = lo;
        if (z.t > 0.0f) {
            const float s_lh = cycles_schlick_ior_s(r.lo, j, z.hi);
            hi = s_lh + (r.t > 0.0f ? (cycles_schlick_ior_s(r.hi, j, z.hi) - s_lh) * r.t : 0.0f);
        }
        model_stack_table_store(STACK_TABLE_CYCLES_COAT_S + j, lo + (hi - lo) * z.t);
    }
}
GONIO_INLINE void cycles_principled_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_CYCLES_ENERGY) == 0u || table_stack_shape(s) != TABLE_SHAPE_TWO_LAYER_OPAQUE) return;
    const CoatParams p = coat_params(s.layers[0], s.layers[1]);
    cycles_store_e_set(STACK_TABLE_CYCLES_COAT_E, p.alpha0);
    if (p.base_kind == KIND_CONDUCTOR) cycles_store_e_set(STACK_TABLE_CYCLES_BASE_E, p.alpha1);
    if (p.eta > 1.0f) cycles_store_schlick_set(p);   // the coat's albedo estimate reads the table above IOR 1 only
}
#define GONIO_MODEL_TABLES(s, sets) cycles_principled_tables(s, sets)
#endif
#endif
