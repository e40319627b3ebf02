// gonio-model: tm21
// citation: Randrianandrasana, Callet & Lucas 2021, ACM TOG 40(4) (two-flux transfer matrices, the authors' tm2)
// family: transfer matrices
// summary: lobe energies from 2x2 transfer matrices of FGD/TIR albedos, roughness from Henyey-Greenstein asymmetry
//   through the same matrices, exact top lobe; separable Smith G in the lobes below and the tables (as the authors'
//   code)
// stacks: dielectric interfaces (absorbing media: gonio's extension) over a conductor base
// represents: dielectric-stack-over-conductor
// reciprocal: no
// energy-conserving: no (as belcour18-toplobe: the exact lobe 0 and the table's FGD differ near grazing (not
//   bounded by construction; no excess found on the hard cases: largest 0.996))
// variant: +g2 = convention g2: with height-correlated Smith G2 in its lobes below lobe 0 and in the FGD/TIR tables
//   (gonio's alternative to the separable G of the authors' code)
// variant-energy-note: +g2 = as tm21 (not bounded by construction; no excess found on the hard cases: largest
//   0.996)
// plan: lobes
// refuses: scattering-medium = {id}: the authors' two-flux tm2 takes no medium ({layer}); their six-flux tm6 has
//   Henyey-Greenstein media, not implemented
// refuses: lambertian-base = {id} (two-flux, tm2) takes dielectric interfaces over a conductor; a Lambertian base
//   needs the authors' six-flux variant, not implemented
// refuses: transmissive = {id}: the transmissive variant (the authors' tm2_dielectric) is not implemented
//
// models/builtin/07-tm21.glsl: `tm21`, Randrianandrasana, Callet & Lucas 2021, "Transfer Matrix Based Layered Materials
// Rendering" (ACM TOG 40(4)), its two-flux model for opaque stacks (the authors' `tm2` plugin).
// Each interface is a component with downward/upward reflection and transmission (r, t, r', t'): an energy
// (FGD from gonio's tables, t = 1 - r, the same both ways) and a Henyey-Greenstein asymmetry g standing for the
// lobe's roughness. The stack's reflectance is read from the product of the components' 2 x 2 transfer matrices
//   M = (1 / t) [[1, -r'], [r, t t' - r r']],   R_0i = M21 / M11,
//   R over a conductor r_c = (M21 + M22 r_c) / (M11 + M12 r_c)
// and the same algebra on the energy-weighted asymmetries (r g, t g, ...) gives the cumulated g. Lobe i has
// energy e_i = R_0i - R_0(i-1) and asymmetry g_i = (G_0i - G_0(i-1)) / mean(e_i), drawn as a GGX lobe of roughness
// hg_to_ggx(g_i); lobe 0 is the exact top-interface BRDF (the authors adopt Bati et al. 2019's correction).
// Transmitted asymmetries are replaced by first-order terms (a lobe refracted down, reflected by the next
// component and refracted back up), and the TIR table moves energy from t to r on the denser side.
// Conventions (docs/MODELS.md): FGD/TIR from gonio's tables and the lobes below lobe 0 with separable Smith
// G1(l) G1(v), as the authors' code (tm2.cpp:273 ndf.G, Mitsuba 0.6's separable G; tm_TIR.bin is tabulated with
// it), or with height-correlated G2 in both (CONVENTION_G2, `tm21+g2`); lobe 0 is the reference's exact top
// interface (height-correlated, where tm2.cpp:251 uses the separable G).
// gonio's choices (docs/MODELS.md): an absorbing medium (tm2 has none; tm6 handles scattering media) is a
// component with r = 0, t = t' = exp(-tau / mu), g = 1; an index-matched interface is no component; the mean
// direction totally reflected ends the stack there.
// The includer provides what belcour18.glsl needs (model_layer, model_layer_count, model_fgd / model_tir).
#ifndef GONIO_MODEL_TM21_GLSL
#define GONIO_MODEL_TM21_GLSL
#include "models/belcour18.glsl"

// GGX roughness <-> Henyey-Greenstein asymmetry, the authors' fits.
GONIO_INLINE float tm_hg_from_ggx(float alpha) {
    float a = clamp(alpha, 0.0f, 1.0f);
    return clamp(-0.085f + 1.085f / (1.0f + pow(a / 0.5f, 1.3f)), 0.0f, 1.0f);
}
GONIO_INLINE float tm_hg_to_ggx(float g) {
    float x = 1.085f / (max(clamp(g, -1.0f, 1.0f), 0.2f) + 0.085f) - 1.0f;
    return clamp(0.5f * pow(max(x, 0.0f), 1.0f / 1.3f), 1e-4f, 1.0f);
}
// The asymmetry of a lobe refracted into a medium of relative index eta.
GONIO_INLINE float tm_hg_refract(float g, float eta) {
    return min(sqrt(max(1.0f - (1.0f - g * g) * pow(eta, 0.75f), 0.0f)), 1.0f);
}

struct TmEnergy { vec3 m11, m12, m21, m22; };
struct TmAsym { float m11, m12, m21, m22; };

GONIO_INLINE TmEnergy tm_energy_mul(TmEnergy a, TmEnergy b) {
    TmEnergy c;
    c.m11 = a.m11 * b.m11 + a.m12 * b.m21;
    c.m12 = a.m11 * b.m12 + a.m12 * b.m22;
    c.m21 = a.m21 * b.m11 + a.m22 * b.m21;
    c.m22 = a.m21 * b.m12 + a.m22 * b.m22;
    return c;
}
GONIO_INLINE TmAsym tm_asym_mul(TmAsym a, TmAsym b) {
    TmAsym c;
    c.m11 = a.m11 * b.m11 + a.m12 * b.m21;
    c.m12 = a.m11 * b.m12 + a.m12 * b.m22;
    c.m21 = a.m21 * b.m11 + a.m22 * b.m21;
    c.m22 = a.m21 * b.m12 + a.m22 * b.m22;
    return c;
}
// The transfer matrix of a component (r, t, r', t'); t is bounded away from 0 by the caller.
GONIO_INLINE TmEnergy tm_energy_matrix(vec3 r, vec3 t, vec3 rp, vec3 tp) {
    TmEnergy m;
    vec3 inv = vec3(1.0f) / t;
    m.m11 = inv;
    m.m12 = -rp * inv;
    m.m21 = r * inv;
    m.m22 = (t * tp - r * rp) * inv;
    return m;
}
GONIO_INLINE TmAsym tm_asym_matrix(float r, float t, float rp, float tp) {
    TmAsym m;
    float inv = 1.0f / max(t, 1e-7f);
    m.m11 = inv;
    m.m12 = -rp * inv;
    m.m21 = r * inv;
    m.m22 = (t * tp - r * rp) * inv;
    return m;
}

// The reflectance of the stack so far (energies E, asymmetries G) over a component that transmits nothing, of
// reflectance rc (energy) or rg (energy-weighted asymmetry): (M21 + M22 r_c) / (M11 + M12 r_c).
GONIO_INLINE vec3 tm_energy_over(TmEnergy E, vec3 rc) {
    return (E.m21 + E.m22 * rc) / (E.m11 + E.m12 * rc);
}
GONIO_INLINE float tm_asym_over(TmAsym G, float rg) {
    return (G.m21 + G.m22 * rg) / (G.m11 + G.m12 * rg);
}

// The conductor base (layer i, cosine cti above it) under the stack so far: the cumulated energy and asymmetry.
GONIO_INLINE void tm21_conductor_base(LayerGpu L, uint i, float cti, float alpha, bool tables, TmEnergy E, TmAsym G,
                                      OUT(vec3) e_cum, OUT(float) g_cum) {
    vec3 c0 = layer_conductor_eta(L), c1 = layer_conductor_k(L);
    vec3 rc = tables ? model_fgd(i, cti, alpha) : fresnel_conductor(cti, c0, c1);
    e_cum = tm_energy_over(E, rc);
    float rg = avg3(rc) * tm_hg_from_ggx(alpha);
    g_cum = tm_asym_over(G, rg);
}

// The transmitted asymmetries of interface i (cosines cti above, ctt below) per unit of the asymmetry g_T arriving:
// tg down, tpg up. "Fake" rough transmissions carried by first-order terms (down through this interface, off the
// next component, back up); g_Tj is the asymmetry transmitted down, g_TjR that reflected back up by the next
// component.
GONIO_INLINE void tm21_transmitted_asymmetries(uint i, uint n, float eta, float alpha, float cti, float ctt, float g_T,
                                               OUT(float) tg, OUT(float) tpg, OUT(float) g_Tj, OUT(float) g_TjR) {
    // "fake" rough transmissions: the reflection lobe scaled by 0.5 |1 - eta_i cos_i / (eta_t cos_t)|
    float tg_fake = tm_hg_from_ggx(0.5f * abs(1.0f - cti / (eta * ctt)) * alpha);
    float tpg_fake = tm_hg_from_ggx(0.5f * abs(1.0f - eta * ctt / cti) * alpha);
    // first-order terms: down through this interface, off the next component, back up
    float next_rg = i + 1u < n ? tm_hg_from_ggx(layer_alpha(model_layer(i + 1u))) : 1.0f;
    g_Tj = tm_hg_refract(g_T, 1.0f / eta) * tg_fake;
    g_TjR = g_Tj * next_rg;
    float g_TjRT = tm_hg_refract(g_TjR, eta) * tpg_fake;
    tg = g_T != 0.0f ? g_Tj / g_T : 0.0f;
    tpg = g_TjR != 0.0f ? g_TjRT / g_TjR : 0.0f;
}

// Total internal reflection on the denser side of interface i, from the TIR table at the roughness of the light
// arriving there (g_T from above, g_TjR from below): energy moved from t to r.
GONIO_INLINE void tm21_trap_tir(uint i, float eta, float cti, float ctt, float g_T, float g_TjR, INOUT(vec3) r,
                                INOUT(vec3) t, INOUT(vec3) rp, INOUT(vec3) tp) {
    if (eta < 1.0f) {
        vec3 trapped = (1.0f - model_tir(i, cti, tm_hg_to_ggx(g_T))) * t;
        r += trapped;
        t -= trapped;
    } else {
        vec3 trapped = (1.0f - model_tir(i, ctt, tm_hg_to_ggx(g_TjR))) * tp;
        rp += trapped;
        tp -= trapped;
    }
}

// A dielectric interface i that transmits the mean direction (cosines cti above, ctt below; reflectance r): its
// component (r, t = 1 - r, r' = r, t' = t and their asymmetries) multiplied into the stack's E and G; g_T becomes
// the asymmetry transmitted below it.
GONIO_INLINE void tm21_dielectric_component(uint i, uint n, float eta, float alpha, float cti, float ctt, vec3 r,
                                            bool tables, INOUT(TmEnergy) E, INOUT(TmAsym) G, INOUT(float) g_T) {
    vec3 t = vec3(1.0f) - r, rp = r, tp = t;
    float rg = tm_hg_from_ggx(alpha), rpg = rg;
    float tg, tpg, g_Tj, g_TjR;
    tm21_transmitted_asymmetries(i, n, eta, alpha, cti, ctt, g_T, tg, tpg, g_Tj, g_TjR);
    if (tables) tm21_trap_tir(i, eta, cti, ctt, g_T, g_TjR, r, t, rp, tp);
    t = max(t, vec3(1e-7f));
    E = tm_energy_mul(E, tm_energy_matrix(r, t, rp, tp));
    G = tm_asym_mul(G, tm_asym_matrix(rg * avg3(r), tg * avg3(t), rpg * avg3(rp), tpg * avg3(tp)));
    g_T = g_Tj;
}

// The medium under an interface (optical depth tau, cosine cti in it) as a component: r = 0, t = t' = exp(-tau / mu),
// no widening (g = 1).
GONIO_INLINE void tm21_medium_component(vec3 tau, float cti, INOUT(TmEnergy) E, INOUT(TmAsym) G) {
    vec3 tm = max(exp(-tau / cti), vec3(1e-30f));
    E = tm_energy_mul(E, tm_energy_matrix(vec3(0.0f), tm, vec3(0.0f), tm));
    float ta = avg3(tm);
    G = tm_asym_mul(G, tm_asym_matrix(0.0f, ta, 0.0f, ta));
}

// Lobe i from the cumulated reflectance and asymmetry down to its component and down to the one above: energy
// e_i = R_0i - R_0(i-1), roughness hg_to_ggx of g_i = (G_0i - G_0(i-1)) / mean(e_i).
GONIO_INLINE void tm21_lobe(vec3 e_cum, vec3 e_prev, float g_cum, float g_prev, OUT(vec3) e, OUT(float) alpha) {
    e = max(e_cum - e_prev, vec3(0.0f));
    float ea = avg3(e);
    float g = ea > 0.0f ? min((g_cum - g_prev) / ea, 1.0f) : 0.0f;
    alpha = ea > 0.0f ? tm_hg_to_ggx(g) : 0.0f;
}

// The lobes for light arriving with cosine mu, in belcour18.glsl's BelcourLobes (no transmitted lobe).
GONIO_INLINE BelcourLobes tm21_lobes(float mu, bool tables) {
    BelcourLobes b;
    b.count = 0u;
    b.e_t = vec3(0.0f);
    b.alpha_t = 0.0f;
    TmEnergy E;
    E.m11 = vec3(1.0f); E.m12 = vec3(0.0f); E.m21 = vec3(0.0f); E.m22 = vec3(1.0f);
    TmAsym G;
    G.m11 = 1.0f; G.m12 = 0.0f; G.m21 = 0.0f; G.m22 = 1.0f;
    vec3 e_prev = vec3(0.0f);
    float g_prev = 0.0f;
    float g_T = 1.0f;   // first-order asymmetry of the light transmitted down to here
    float cti = clamp(mu, 1e-4f, 1.0f);
    uint n = model_layer_count();
    for (uint i = 0u; i < n; ++i) {
        LayerGpu L = model_layer(i);
        float alpha = layer_alpha(L);
        vec3 e_cum;
        float g_cum;
        bool last = false;
        uint kind = layer_kind(L);
        if (kind != KIND_CONDUCTOR && kind != KIND_DIELECTRIC) {
            // no component for this kind (model_cannot_represent refuses it): NaN
            b.e[i] = vec3(model_nan());
            b.alpha[i] = model_nan();
            b.count = i + 1u;
            break;
        }
        if (kind == KIND_CONDUCTOR) {
            tm21_conductor_base(L, i, cti, alpha, tables, E, G, e_cum, g_cum);
            last = true;
        } else {
            float eta = layer_eta(L);
            if (abs(eta - 1.0f) < 1e-5f) {   // index-matched: no component, no lobe
                b.e[i] = vec3(0.0f);
                b.alpha[i] = 0.0f;
                b.count = i + 1u;
                continue;
            }
            float ctt = refracted_cos(cti, eta);
            vec3 r = tables ? model_fgd(i, cti, alpha) : vec3(fresnel_dielectric(cti, eta));
            if (!(ctt > 0.0f)) {   // the mean direction is totally reflected: nothing goes below
                r = vec3(1.0f);
                e_cum = tm_energy_over(E, r);
                float rg = tm_hg_from_ggx(alpha);
                g_cum = tm_asym_over(G, rg);
                last = true;
            } else {
                ctt = max(ctt, 1e-4f);
                tm21_dielectric_component(i, n, eta, alpha, cti, ctt, r, tables, E, G, g_T);
                e_cum = E.m21 / E.m11;
                g_cum = G.m21 / G.m11;
                cti = ctt;
            }
        }
        vec3 e;
        float lobe_alpha;
        tm21_lobe(e_cum, e_prev, g_cum, g_prev, e, lobe_alpha);
        b.e[i] = e;
        b.alpha[i] = lobe_alpha;
        b.count = i + 1u;
        if (last) break;
        e_prev = e_cum;
        g_prev = g_cum;
        // the medium under interface i
        vec3 tau = layer_optical_depth(L);
        if (i + 1u < n && (tau.x > 0.0f || tau.y > 0.0f || tau.z > 0.0f)) tm21_medium_component(tau, cti, E, G);
    }
    return b;
}

// f(l, v) through the lobes (CPU twin; the device reads the lobes precomputed per dispatch): exact lobe 0,
// lobes below from the transfer matrices.
GONIO_INLINE vec3 model_tm21(uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
    BelcourLobes b = tm21_lobes(l.z, model_use_tables());
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) f += top_interface_reflection(model_layer(0u), l, v);
    if ((terms & TERM_BASE) != 0u)
        for (uint k = 1u; k < b.count; ++k)
            if (b.e[k].x + b.e[k].y + b.e[k].z > 0.0f) f += b.e[k] * belcour_lobe(l, v, b.alpha[k]);
    return f;
}
// The entry (models/all.glsl): on the device the lobes precomputed once per dispatch (models.comp KERNEL 2, from
// tm21_lobes above: GONIO_MODEL_LOBES) and read back as Belcour's top-lobe variant reads them (exact lobe 0, lobes
// below); on the CPU twin model_tm21 above.
#define GONIO_MODEL_LOBES(mu, tables) tm21_lobes(mu, tables)
GONIO_INLINE vec3 model_tm21(CoatParams p, uint terms, vec3 l, vec3 v) {
#if defined(BELCOUR_LOBES_OF_MU)
    return model_belcour18_lobes_of_mu(BELCOUR_TOPLOBE, terms, l, v);   // render.comp: lobes at mu = cos theta_l
#elif defined(BELCOUR_PRECOMPUTED_LOBES)
    return model_belcour18_precomputed(BELCOUR_TOPLOBE, terms, l, v);
#else
    return model_tm21(terms, l, v);
#endif
}
#endif
