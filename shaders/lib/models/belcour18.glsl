// models/belcour18.glsl: Belcour 2018, "Efficient rendering of layered materials using an atomic
// decomposition with statistical operators" (ACM TOG 37(4), 73), and Bati et al. 2019's fix of it (section 4.2).
// The light is a bundle with energy (RGB), mean (a cosine) and variance (a scalar in Belcour's linearised
// space, section 4); each interface and medium updates them with atomic operators (reflection, refraction,
// absorption: Table 1) and the adding procedure (section 6, eqs. 24-27) combines layers with their
// inter-reflections. The BRDF is a sum of GGX lobes, one per interface that reflects:
//   f(l, v) = sum_k e_k D(h; alpha_k) G(l, v; alpha_k) / (4 l.z v.z),   alpha_k = sigma^-1(sigma_k)
// The loop follows the reference code's order as its ports carry it (research notes, models.md section 1.4):
// R12 from FGD queried with the roughness of the incident lobe, the TIR table applied to Ri0/Ti0 at interface
// i > 0 for the way back up through interface i - 1, the transmitted roughness scale
// 0.5 |n12 - 1| / n12 (down) and 0.5 |1 - n12| (up) with the cosines inside set to 1 ("_ctt = _cti = 1"),
// and the refraction Jacobians j12 = n12 ctt / cti. Choices of gonio, documented in docs/MODELS.md:
//   * gonio's layer = interface + the medium under it: the medium is its own step (absorption and forward
//     scattering along the mean direction, Table 1, as the reference code's volume layer), right after its interface;
//   * the inter-reflection denominator is tested per channel (Unity StackLit), cosines clamped at 1e-4;
//   * a dielectric interface under total internal reflection of the mean direction ends the loop
//     (nothing reaches the layers below), as a conductor does;
//   * transmissive stacks (a slab: substrate IOR = exterior IOR) also get the transmitted lobe, energy T0n
//     and variance s_T0n, drawn as a GGX lobe about the straight-through direction (the mirror lobe of
//     roughness alpha_T flipped through the surface plane);
//   * without tables (ModelOptions::belcour_tables = false), R12 is the exact Fresnel factor at the mean cosine and
//     there is no TIR term.
// Conventions (model_convention(), docs/MODELS.md "Conventions"): by default what the official code computes,
// separable Smith G1(l) G1(v) in the lobes and the tables, and no TIR term for an interface with an absorbing
// medium under it; CONVENTION_G2 (`+g2`): height-correlated G2 in both; CONVENTION_TIR_BELOW_MEDIA (`+tir`): the
// TIR term kept there.
// Variants: forward (statistics from cos theta_l), symmetric (from |h.l|, h = normalize(l + v): section 7.2,
// reciprocal), top-lobe (Bati et al. 2019 section 4.2: the exact top-interface BRDF f_r0 for lobe 0, the
// forward model for the others).
// The includer provides: uint model_layer_count(), LayerGpu model_layer(uint i), bool model_use_tables(),
// float model_table(uint index), uint model_convention().
#ifndef GONIO_MODEL_BELCOUR18_GLSL
#define GONIO_MODEL_BELCOUR18_GLSL
#include "common.glsl"
#include "belcour_tables.glsl"

const uint BELCOUR_FORWARD = 0u;
const uint BELCOUR_SYMMETRIC = 1u;
const uint BELCOUR_TOPLOBE = 2u;
// Precomputed lobes on the device (see BELCOUR_PRECOMPUTED_LOBES below): vec4s per node of mu (lobes, transmitted
// lobe, count); the nodes (BELCOUR_MU_NODES, belcour_mu_node) are in kernel_interface.glsl.
const uint BELCOUR_LOBE_STRIDE = MAX_LAYERS + 2u;

// Roughness <-> linearised variance (Belcour 2018, eq. 20's fit; belcour/shaderlib layer.shader):
// sigma = a^1.1 / (1 - a^1.1). alpha is clamped below 1, where sigma diverges.
GONIO_INLINE float belcour_roughness_to_variance(float alpha) {
    float a = pow(clamp(alpha, 0.0f, 0.9999f), 1.1f);
    return a / (1.0f - a);
}
// The linearised variance of a Henyey-Greenstein medium of asymmetry g, ((1 - g) / g)^0.8 / (1 + g) (Belcour 2018
// section 5; Photon-v2 LaurentBelcour/conversions.h g_to_variance), defined for g in (0, 1] (0 at g = 1, no blur):
// NaN for a medium that does not scatter forward (the models refuse it, model_applicability.cpp).
GONIO_INLINE float belcour_hg_variance(float g) {
    if (!(g > 0.0f && g <= 1.0f)) return model_nan();
    return pow((1.0f - g) / g, 0.8f) / (1.0f + g);
}

GONIO_INLINE float belcour_variance_to_roughness(float sigma) {
    float s = max(sigma, 0.0f);
    if (!(s < 1e30f)) return 1.0f;
    return pow(s / (1.0f + s), 1.0f / 1.1f);
}

GONIO_INLINE float avg3(vec3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

struct BelcourLobes {
    vec3 e[MAX_LAYERS];       // energy of lobe k (reflection off interface k, seen from the top)
    float alpha[MAX_LAYERS];  // its GGX roughness
    uint count;               // lobes written
    vec3 e_t;                 // transmitted energy (transmissive stacks that are not cut by TIR)
    float alpha_t;            // roughness of the transmitted lobe
};

// The adding state of the layers above: stack [0..i] reflect/transmit downward (0i) and upward (i0).
struct BelcourState {
    vec3 R0i, Ri0, T0i, Ti0;
    float s_r0i, s_ri0, s_t0i, s_ti0;   // linearised variances
    float j0i, ji0;                     // accumulated refraction Jacobians
};

// Adds one step (interface or medium) with its own R12, T12, R21, T21 and variances below the state
// (Belcour 2018 section 6, in the reference code's form). Returns the new lobe's energy in e_lobe and its
// variance in s_lobe (the light of this step seen from the top; zero for a medium).
GONIO_INLINE void belcour_add(INOUT(BelcourState) st, vec3 R12, vec3 T12, vec3 R21, vec3 T21, float s_r12,
                              float s_r21, float s_t12, float s_t21, float j12, float j21, OUT(vec3) e_lobe,
                              OUT(float) s_lobe) {
    vec3 denom = vec3(1.0f) - st.Ri0 * R12;
    vec3 inv = vec3(denom.x > 0.0f ? 1.0f / denom.x : 0.0f, denom.y > 0.0f ? 1.0f / denom.y : 0.0f,
                    denom.z > 0.0f ? 1.0f / denom.z : 0.0f);
    vec3 m_R0i = st.T0i * R12 * st.Ti0 * inv;
    vec3 m_Ri0 = T21 * st.Ri0 * T12 * inv;
    vec3 m_Rr = st.Ri0 * R12 * inv;
    vec3 e_R0i = st.R0i + m_R0i, e_T0i = st.T0i * T12 * inv;
    vec3 e_Ri0 = R21 + m_Ri0, e_Ti0 = T21 * st.Ti0 * inv;
    float r0i = avg3(st.R0i), e_r0i = avg3(e_R0i), e_ri0 = avg3(e_Ri0);
    float m_r0i = avg3(m_R0i), m_ri0 = avg3(m_Ri0), m_rr = avg3(m_Rr), r21 = avg3(R21);

    float lobe = st.s_ti0 + st.j0i * (st.s_t0i + s_r12 + m_rr * (s_r12 + st.s_ri0));
    float s_r0i = r0i * st.s_r0i + m_r0i * lobe;
    float s_t0i = j12 * st.s_t0i + s_t12 + j12 * (s_r12 + st.s_ri0) * m_rr;
    float s_ri0 = r21 * s_r21 + m_ri0 * (s_t12 + j12 * (s_t21 + st.s_ri0 + m_rr * (s_r12 + st.s_ri0)));
    float s_ti0 = st.ji0 * s_t21 + st.s_ti0 + st.ji0 * (s_r12 + st.s_ri0) * m_rr;
    e_lobe = m_r0i > 0.0f ? m_R0i : vec3(0.0f);
    s_lobe = lobe;

    st.R0i = e_R0i; st.T0i = e_T0i; st.Ri0 = e_Ri0; st.Ti0 = e_Ti0;
    st.s_r0i = e_r0i > 0.0f ? s_r0i / e_r0i : 0.0f;
    st.s_ri0 = e_ri0 > 0.0f ? s_ri0 / e_ri0 : 0.0f;
    st.s_t0i = s_t0i;
    st.s_ti0 = s_ti0;
    st.j0i *= j12;
    st.ji0 *= j21;
}

GONIO_INLINE void belcour_begin(OUT(BelcourState) st) {
    st.R0i = vec3(0.0f); st.Ri0 = vec3(0.0f); st.T0i = vec3(1.0f); st.Ti0 = vec3(1.0f);
    st.s_r0i = 0.0f; st.s_ri0 = 0.0f; st.s_t0i = 0.0f; st.s_ti0 = 0.0f;
    st.j0i = 1.0f; st.ji0 = 1.0f;
}

// Adds layer i (its interface, then the medium under it) to the state, for light whose mean direction arrives
// at the interface with cosine cti (updated to the cosine below it). Writes the lobe of interface i (energy,
// roughness). Returns false when nothing goes below (a conductor, or total internal reflection of the mean).
GONIO_INLINE bool belcour_layer(INOUT(BelcourState) st, INOUT(float) cti, uint i, uint n, bool tables,
                                OUT(vec3) e_lobe, OUT(float) alpha_lobe) {
    LayerGpu L = model_layer(i);
    uint kind = layer_kind(L);
    // a conductor or a dielectric; any other kind has no operator here (model_cannot_represent refuses it): NaN
    if (kind != KIND_CONDUCTOR && kind != KIND_DIELECTRIC) {
        e_lobe = vec3(model_nan());
        alpha_lobe = model_nan();
        return false;
    }
    bool conductor = kind == KIND_CONDUCTOR;
    float alpha = layer_alpha(L);
    vec3 c0 = layer_conductor_eta(L), c1 = layer_conductor_k(L);
    float n12 = conductor ? avg3(c0) : layer_eta(L);
    // the mean direction: Snell on the cosine (Table 1), -1 under total internal reflection
    float sti = sqrt(max(0.0f, 1.0f - cti * cti));
    float stt = sti / n12;
    float ctt = (!conductor && stt < 1.0f) ? sqrt(1.0f - stt * stt) : -1.0f;
    bool has_t = ctt > 0.0f;
    float s_r12 = belcour_roughness_to_variance(alpha), s_t12 = 0.0f, s_t21 = 0.0f, j12 = 1.0f, j21 = 1.0f;
    if (has_t) {
        s_t12 = belcour_roughness_to_variance(alpha * 0.5f * abs(n12 - 1.0f) / n12);
        s_t21 = belcour_roughness_to_variance(alpha * 0.5f * abs(1.0f - n12));
        ctt = max(ctt, 1e-4f);
        j12 = ctt / cti * n12;
        j21 = cti / ctt / n12;
    }
    // FGD is queried with the roughness of the incident lobe (reference code: temp_alpha)
    float temp_alpha = belcour_variance_to_roughness(st.s_t0i + s_r12);
    vec3 R12;
    if (tables) R12 = model_fgd(i, cti, temp_alpha);
    else if (conductor) R12 = fresnel_conductor(cti, c0, c1);
    else R12 = vec3(fresnel_dielectric(cti, n12));
    vec3 T12 = conductor ? vec3(0.0f) : vec3(1.0f) - R12;
    vec3 R21 = R12, T21 = T12;
    if (!has_t) { R21 = vec3(0.0f); T21 = vec3(0.0f); T12 = vec3(0.0f); }
    // total internal reflection on the way back up through interface i - 1 (from its denser side only). The
    // official code takes it from the IORs of the two layers above this interface, where a medium is a layer of its
    // own with the IOR of the one above it (Photon-v2 InterfaceStatistics.cpp:81-86 `n10 = layer0 / layer1`,
    // LbLayer.h:80-93; the same `n10 = eta_0 / eta_1` in the Arnold copy of the supplemental code): below an
    // absorbing medium n10 = 1 and the term vanishes. That is the default; CONVENTION_TIR_BELOW_MEDIA keeps it.
    LayerGpu above = model_layer(i > 0u ? i - 1u : 0u);
    vec3 tau_above = layer_optical_depth(above);
    bool medium_above = tau_above.x > 0.0f || tau_above.y > 0.0f || tau_above.z > 0.0f;
    bool tir_here = !medium_above || (model_convention() & CONVENTION_TIR_BELOW_MEDIA) != 0u;
    if (i > 0u && tables && tir_here && layer_kind(above) == KIND_DIELECTRIC && layer_eta(above) > 1.0f) {
        float tir = model_tir(i - 1u, cti, temp_alpha);
        st.Ri0 = clamp(st.Ri0 + (1.0f - tir) * st.Ti0, vec3(0.0f), vec3(1.0f));
        st.Ti0 *= tir;
    }
    float s_lobe;
    belcour_add(st, R12, T12, R21, T21, s_r12, s_r12, s_t12, s_t21, j12, j21, e_lobe, s_lobe);
    alpha_lobe = belcour_variance_to_roughness(s_lobe);
    if (!has_t) return false;
    cti = ctt;
    // the medium under interface i, the reference code's volume layer as its ports carry it (Photon-v2
    // InterfaceStatistics.cpp addLayer, the !isSurface() branch; Table 1's absorption and forward scattering):
    // along the mean direction T = (1 + sigma_s d / cos) exp(-sigma_t d / cos), with sigma_t d = tau and
    // sigma_s d = albedo tau; no reflection (the light a medium scatters back is not represented: "limited to forward
    // propagation"); the transmitted variance grows by the Henyey-Greenstein one where the medium scatters. A
    // medium that only absorbs (albedo 0) is Beer-Lambert with variance 0 (Photon's default g = 1).
    vec3 tau = layer_optical_depth(L);
    if (i + 1u < n && (tau.x > 0.0f || tau.y > 0.0f || tau.z > 0.0f)) {
        vec3 omega = layer_scattering_albedo(L);
        vec3 t = (vec3(1.0f) + omega * tau / cti) * exp(-tau / cti);
        float s_hg = layer_medium_scatters(L) ? belcour_hg_variance(layer_phase_g(L)) : 0.0f;
        vec3 e0;
        float s0;
        belcour_add(st, vec3(0.0f), t, vec3(0.0f), t, 0.0f, 0.0f, s_hg, s_hg, 1.0f, 1.0f, e0, s0);
    }
    return true;
}

// The lobes of the whole stack for light arriving with cosine mu (Belcour 2018 section 6).
GONIO_INLINE BelcourLobes belcour_lobes(float mu, bool tables) {
    BelcourLobes b;
    b.count = 0u;
    b.e_t = vec3(0.0f);
    b.alpha_t = 0.0f;
    BelcourState st;
    belcour_begin(st);
    float cti = clamp(mu, 1e-4f, 1.0f);
    uint n = model_layer_count();
    bool through = true;   // the mean direction reached below the last interface
    for (uint i = 0u; i < n; ++i) {
        vec3 e;
        float a;
        bool more = belcour_layer(st, cti, i, n, tables, e, a);
        b.e[i] = e;
        b.alpha[i] = a;
        b.count = i + 1u;
        if (!more) { through = false; break; }
    }
    if (through) {
        b.e_t = st.T0i;
        b.alpha_t = belcour_variance_to_roughness(st.s_t0i);
    }
    return b;
}

// One GGX lobe with F = 1 (its energy is in e_k), evaluated in the macro-normal frame, with the model's
// masking-shadowing: separable G1(l) G1(v) by default, as the official codes evaluate their lobes (Photon-v2
// LbLayeredSurface.cpp:30-33 make_ggx, EMaskingShadowing::Separable, "the reference implementation ... uses
// Mitsuba, which is using the separable Smith G1"; TMbLM-Rendering tm2.cpp:273 ndf.G, Mitsuba 0.6 microfacet.h
// MicrofacetDistribution::G = smithG1(wi) smithG1(wo)), or height-correlated G2 (CONVENTION_G2).
GONIO_INLINE float belcour_lobe(vec3 l, vec3 v, float alpha) {
    float a = max(alpha, MODEL_MIN_ALPHA);
    vec3 h = normalize(l + v);
    float g = (model_convention() & CONVENTION_G2) != 0u ? ggx_G2(l, v, a) : ggx_G2_separable(l, v, a);
    return ggx_D(h, a) * g / (4.0f * l.z * v.z);
}

// f(l, v): reflection for v.z > 0, transmission (transmissive stacks) for v.z < 0.
// TERM_TOP is lobe 0, TERM_BASE everything else (the lobes of the interfaces below, and the transmitted lobe).
// Each lobe is added as the adding loop produces it (no arrays: lavapipe keeps those in memory, 5x slower).
GONIO_INLINE vec3 model_belcour18(uint variant, uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z == 0.0f) return vec3(0.0f);
    bool tables = model_use_tables();
    bool transmission = v.z < 0.0f;
    if (transmission && ((terms & TERM_BASE) == 0u || variant == BELCOUR_SYMMETRIC)) return vec3(0.0f);
    float mu = l.z;
    if (variant == BELCOUR_SYMMETRIC) mu = abs(dot(l, normalize(l + v)));
    BelcourState st;
    belcour_begin(st);
    float cti = clamp(mu, 1e-4f, 1.0f);
    uint n = model_layer_count();
    vec3 f = vec3(0.0f);
    bool through = true;
    for (uint i = 0u; i < n; ++i) {
        vec3 e;
        float a;
        bool more = belcour_layer(st, cti, i, n, tables, e, a);
        if (!transmission && (terms & (i == 0u ? TERM_TOP : TERM_BASE)) != 0u) {
            if (i == 0u && variant == BELCOUR_TOPLOBE) {
                f += top_interface_reflection(model_layer(0u), l, v);
            } else if (e.x + e.y + e.z > 0.0f) {
                f += e * belcour_lobe(l, v, a);
            }
        }
        if (!more) { through = false; break; }
    }
    if (transmission && through)
        f = st.T0i * belcour_lobe(l, vec3(v.x, v.y, -v.z), belcour_variance_to_roughness(st.s_t0i));
    return f;
}

#ifdef BELCOUR_PRECOMPUTED_LOBES
// The symmetric variant's lobes depend on (l, v) only through mu = |h.l|: the device tabulates them at
// BELCOUR_MU_NODES nodes mu = (i / (N - 1))^2 once per dispatch (models.comp, KERNEL 2) and this interpolates
// them linearly in sqrt(mu) (energies and roughnesses). The nodes are quadratic because the lobes change fastest
// towards grazing (conductor Fresnel, FGD): with nodes uniform in mu, a mirror lobe at 89.9 degrees (mu = 0.0017)
// fell between the first two nodes and lost 1.4% of its energy. Still reciprocal: h.l = h.v.
// Where mu falls in the table of lobes at the nodes belcour_mu_node: node i and the weight t of node i + 1, linear in
// sqrt(mu). The lobes jump where the mean direction starts to be totally reflected inside the stack (mu below
// model_mu_jump(), 0: nowhere): across the node interval holding the jump, interpolating would blend the two sides,
// so the two nodes on mu's own side are extrapolated instead.
GONIO_INLINE void belcour_mu_table_position(float mu, OUT(uint) i, OUT(float) t) {
    float x = sqrt(mu) * float(BELCOUR_MU_NODES - 1u);
    i = min(uint(x), BELCOUR_MU_NODES - 2u);
    t = x - float(i);
    float mj = model_mu_jump();
    if (mj > belcour_mu_node(i) && mj < belcour_mu_node(i + 1u)) {
        if (mu < mj && i > 0u) { i -= 1u; t += 1.0f; }
        else if (mu >= mj && i + 2u < BELCOUR_MU_NODES) { i += 1u; t -= 1.0f; }
    }
}

GONIO_INLINE vec3 model_belcour18_symmetric_table(uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
    float mu = clamp(abs(dot(l, normalize(l + v))), 0.0f, 1.0f);
    uint i;
    float t;
    belcour_mu_table_position(mu, i, t);
    uint a = i * BELCOUR_LOBE_STRIDE, b = a + BELCOUR_LOBE_STRIDE;
    uint n =
        max(floatBitsToUint(model_lobe(a + MAX_LAYERS + 1u).x), floatBitsToUint(model_lobe(b + MAX_LAYERS + 1u).x));
    vec3 f = vec3(0.0f);
    for (uint k = (terms & TERM_TOP) != 0u ? 0u : 1u; k < ((terms & TERM_BASE) != 0u ? n : min(n, 1u)); ++k) {
        vec4 e = mix(model_lobe(a + k), model_lobe(b + k), t);
        e = max(e, vec4(0.0f));   // extrapolated
        if (e.x + e.y + e.z > 0.0f) f += vec3(e.x, e.y, e.z) * belcour_lobe(l, v, e.w);
    }
    return f;
}

// The forward and top-lobe variants depend on l only through the lobes, the same for a whole dispatch: the
// device computes them once (models.comp, KERNEL 2) and reads them back here, which is what this function
// evaluates. The includer provides vec4 model_lobe(uint k): (e_k, alpha_k), at k = MAX_LAYERS the
// transmitted lobe (e_t, alpha_t), at MAX_LAYERS + 1 the lobe count (bits of x).
GONIO_INLINE vec3 model_belcour18_precomputed(uint variant, uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z == 0.0f) return vec3(0.0f);
    if (v.z < 0.0f) {
        if ((terms & TERM_BASE) == 0u) return vec3(0.0f);
        vec4 t = model_lobe(MAX_LAYERS);
        return vec3(t.x, t.y, t.z) * belcour_lobe(l, vec3(v.x, v.y, -v.z), t.w);
    }
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u) {
        if (variant == BELCOUR_TOPLOBE) {
            f += top_interface_reflection(model_layer(0u), l, v);
        } else {
            vec4 e = model_lobe(0u);
            f += vec3(e.x, e.y, e.z) * belcour_lobe(l, v, e.w);
        }
    }
    if ((terms & TERM_BASE) != 0u) {
        uint n = floatBitsToUint(model_lobe(MAX_LAYERS + 1u).x);
        for (uint k = 1u; k < n; ++k) {
            vec4 e = model_lobe(k);
            if (e.x + e.y + e.z > 0.0f) f += vec3(e.x, e.y, e.z) * belcour_lobe(l, v, e.w);
        }
    }
    return f;
}

#ifdef BELCOUR_LOBES_OF_MU
// The forward and top-lobe variants (and tm21) where l changes from one evaluation to the next (render.comp): their
// lobes depend on l only through mu = cos theta_l, and are read from the same table over mu as the symmetric
// variant's, interpolated as it is (belcour_mu_table_position). Reflection only.
GONIO_INLINE vec3 model_belcour18_lobes_of_mu(uint variant, uint terms, vec3 l, vec3 v) {
    if (l.z <= 0.0f || v.z <= 0.0f) return vec3(0.0f);
    uint i;
    float t;
    belcour_mu_table_position(clamp(l.z, 0.0f, 1.0f), i, t);
    uint a = i * BELCOUR_LOBE_STRIDE, b = a + BELCOUR_LOBE_STRIDE;
    uint n =
        max(floatBitsToUint(model_lobe(a + MAX_LAYERS + 1u).x), floatBitsToUint(model_lobe(b + MAX_LAYERS + 1u).x));
    vec3 f = vec3(0.0f);
    if ((terms & TERM_TOP) != 0u && variant == BELCOUR_TOPLOBE) f += top_interface_reflection(model_layer(0u), l, v);
    uint first = (terms & TERM_TOP) != 0u && variant != BELCOUR_TOPLOBE ? 0u : 1u;
    for (uint k = first; k < ((terms & TERM_BASE) != 0u ? n : min(n, 1u)); ++k) {
        vec4 e = max(mix(model_lobe(a + k), model_lobe(b + k), t), vec4(0.0f));   // max: extrapolated
        if (e.x + e.y + e.z > 0.0f) f += vec3(e.x, e.y, e.z) * belcour_lobe(l, v, e.w);
    }
    return f;
}
#endif
#endif
// The entry of Belcour's forward and top-lobe models: their lobes as the including kernel has them (render.comp,
// BELCOUR_LOBES_OF_MU: tabulated over mu = cos theta_l; models.comp, BELCOUR_PRECOMPUTED_LOBES: at mu = cos theta_i,
// once per dispatch; the CPU twin: computed at each evaluation)
GONIO_INLINE vec3 model_belcour18_entry(uint variant, uint terms, vec3 l, vec3 v) {
#if defined(BELCOUR_LOBES_OF_MU)
    return model_belcour18_lobes_of_mu(variant, terms, l, v);
#elif defined(BELCOUR_PRECOMPUTED_LOBES)
    return model_belcour18_precomputed(variant, terms, l, v);
#else
    return model_belcour18(variant, terms, l, v);
#endif
}
#endif
