// models/fgd_quadrature.glsl: gonio's one quadrature of a rough interface's directional albedo, which
// both of its users call: Belcour 2018's FGD and TIR tables (models/belcour_tables.glsl; shaders/tables.comp on the
// device, host/models/belcour_tables_host.cpp on the CPU twin) and the albedo-scaling model's coat albedo E_coat(mu)
// (host/models/stack_tables.cpp, through this file compiled as C++).
//
// FGD(mu, alpha) = integral over the upper hemisphere of F(l.m) D(m) G(l, v) / (4 l.z v.z) v.z dv,   l.z = mu,
// with the reference's GGX D (ggx.glsl) and exact Fresnel (fresnel.glsl: dielectric, TIR included, or conductor).
// In half-vector space (v = reflect(l, m), dv = 4 (l.m) dm, Walter et al. 2007 eq. 14):
//   FGD = integral over m of F(l.m) D(m) (G(l, v) / l.z) (l.m) dm,
// with tan(theta_m) = alpha (e^(L u) - 1), L = ln(tan(theta_max) / alpha + 1), u uniform (midpoint nodes): nodes
// far finer than alpha near the peak and even steps in log tan theta_m in the tail, up to theta_max =
// (90 degrees + theta_l) / 2, beyond which v = reflect(l, m) is below the horizon for every phi_m (the largest v.z
// at theta_m is cos(2 theta_m - theta_l)); phi_m by midpoint nodes over its visible range (v.z > 0) within [0, pi]
// (the integrand is symmetric about the plane of l). A stratified visible-normal grid converged as 1/N here (3e-3
// off at 64 x 64 nodes, measured).
// Measured against a converged double-precision reference (Gauss-Legendre in phi over the visible range, 8192 u
// nodes x 128, 1e-6 from 4096 x 64), over eta 1.1, 1.33, 1.5, 2, 3 and a gold-like conductor, alpha 1e-4 .. 1, mu at
// every node of both tables: FGD_NODES_THETA x FGD_NODES_PHI = 512 x 32 nodes are at most 1.4e-4 off (both G;
// 1.3e-4 at the coat-albedo nodes; docs/MODELS.md compares other node sets); more nodes do not help in float
// (1024 x 256: 8e-4, rounding). tools/fgd_quadrature_measure.cpp is the measurement.
//
// mu = 0 is the limit mu -> 0+, not a clamped mu: with c = l.z, G / c is finite there, c (1 + Lambda(l)) =
// (c + sqrt(c^2 + alpha^2 (1 - c^2))) / 2 (ggx_lambda with tan^2 = (1 - c^2) / c^2), so
//   height-correlated: G2 / c = 1 / (c (1 + Lambda(l)) + c Lambda(v)),
//   separable:         G1(l) G1(v) / c = G1(v) / (c (1 + Lambda(l))),
// both exact for every c in [0, 1]. FGD approaches that limit over mu ~ alpha (the masking of l near grazing), so
// clamping mu (to 1e-4 or 1e-3) instead would be up to 0.11 off at mu = 0.
// g2: height-correlated Smith G2 = 1 / (1 + Lambda(l) + Lambda(v)) (the reference's), else separable G1(l) G1(v).
// Returns xyz: FGD per channel; w: Belcour's TIR transmitted fraction of a dielectric (belcour_tables.glsl; 1 for a
// conductor), 1 - the share of the F = 1 lobe outside the escape cone sin(theta_v) < eta_c = min(eta, 1 / eta).
#ifndef GONIO_FGD_QUADRATURE_GLSL
#define GONIO_FGD_QUADRATURE_GLSL
#include "common.glsl"

// The nodes both callers use (theta_m, and phi_m over [0, pi]).
const uint FGD_NODES_THETA = 512u;
const uint FGD_NODES_PHI = 32u;

// Which masking-shadowing the quadrature weighs with (fgd_quadrature_sums): the reference's height-correlated G2,
// the separable G1(l) G1(v), or G1(l) alone: then the integral over m of D(m) G1(l) (l.m) / l.z, the visible normals
// of l (Heitz 2018), over the m whose v = reflect(l, m) is above the horizon: a mean over visible normals, as Cycles'
// ggx_gen_schlick tables are made (models/cycles_principled.glsl)
const uint FGD_G2 = 0u;
const uint FGD_SEPARABLE = 1u;
const uint FGD_VISIBLE_NORMALS = 2u;
// A flag added to those: a dielectric's Fresnel F remapped to saturate((F - F0) / (1 - F0)), F0 its normal-incidence
// Fresnel (Cycles' generalized Schlick of exponent -1, the "real Fresnel remapped", in its ggx_gen_schlick_ior_s)
const uint FGD_FRESNEL_REMAPPED = 4u;

// The quadrature's sums: fgd the interface's albedo with its Fresnel, lobe the same with F = 1, tir as fgd_quadrature's w
struct FgdSums {
    vec3 fgd;
    float lobe;
    float tir;
};

GONIO_INLINE FgdSums fgd_quadrature_sums(LayerGpu L, float mu, float alpha, uint g_mode, uint nodes_theta,
                                         uint nodes_phi) {
    FgdSums sums;
    uint kind = layer_kind(L);
    // a conductor or a dielectric; no albedo for another kind (its callers refuse it): NaN
    if (kind != KIND_CONDUCTOR && kind != KIND_DIELECTRIC) {
        sums.fgd = vec3(model_nan());
        sums.lobe = model_nan();
        sums.tir = model_nan();
        return sums;
    }
    float a = max(alpha, MODEL_MIN_ALPHA);
    float c = clamp(mu, 0.0f, 1.0f);
    float s2 = 1.0f - c * c;
    vec3 l = vec3(sqrt(s2), 0.0f, c);
    float c_masking_l = 0.5f * (c + sqrt(c * c + a * a * s2));   // c (1 + Lambda(l)), finite at c = 0
    float eta = layer_eta(L);
    const uint masking = g_mode & 3u;
    const bool remapped = (g_mode & FGD_FRESNEL_REMAPPED) != 0u;
    const float f0 = (eta - 1.0f) * (eta - 1.0f) / ((eta + 1.0f) * (eta + 1.0f));
    float eta_c = kind == KIND_DIELECTRIC ? min(eta, 1.0f / eta) : 2.0f;   // crossing from the denser side
    float z_c = sqrt(max(0.0f, 1.0f - eta_c * eta_c));                          // cos of the escape cone's half-angle
    vec3 cond_eta = layer_conductor_eta(L), cond_k = layer_conductor_k(L);
    // tan(theta_max) = tan(45 degrees + theta_l / 2) = (1 + sin_l) / c, capped at 2e6 (c < 1e-6): the tail beyond
    // adds < 1e-6 (a cap at theta_m = 1.5706, tan = 1e4, missed 2.5e-4 of FGD at mu = 0, alpha = 1)
    float log_range = log((1.0f + l.x) / max(c, 1e-6f) / a + 1.0f);
    vec3 fgd = vec3(0.0f);
    float lobe = 0.0f, outside = 0.0f;
    for (uint i = 0u; i < nodes_theta; ++i) {
        float u = (float(i) + 0.5f) / float(nodes_theta);
        float e = exp(log_range * u);
        float tan_m = a * (e - 1.0f);
        float cos_m = 1.0f / sqrt(1.0f + tan_m * tan_m), sin_m = tan_m * cos_m;
        float dtheta = a * log_range * e * cos_m * cos_m;   // d theta_m / du
        // phi_m over the visible range [0, phi_max] only: v.z = 2 (l.m) cos_m - c > 0 <=> cos(phi_m) >
        // -c cos(2 theta_m) / (sin_l sin(2 theta_m)). The integrand goes to 0 smoothly at phi_max (G ~ v.z), so
        // the midpoint nodes see no cut (over [0, pi] with a cut, near-grazing FGD converged slowly: 3.5e-4 off at
        // 256 x 64 nodes).
        // v.z = sin_l sin(2 theta_m) cos(phi_m) + c cos(2 theta_m), decreasing in phi_m: the escape cone of the TIR
        // term, v.z > z_c = cos(asin(eta_c)), is phi_m < phi_esc likewise.
        float sin_l = l.x, cos_2m = cos_m * cos_m - sin_m * sin_m, sin_2m = 2.0f * sin_m * cos_m;
        float sl2m = sin_l * sin_2m, vz0 = c * cos_2m;
        float cos_phi_max = sl2m > 0.0f ? -vz0 / sl2m : (vz0 > 0.0f ? -1.0f : 1.0f);
        if (cos_phi_max >= 1.0f) continue;
        float phi_max = acos(max(cos_phi_max, -1.0f));
        float dphi = phi_max / float(nodes_phi);
        float half_cell = 0.5f * sl2m * dphi;   // |d v.z / d phi_m| over half a cell, / sin(phi_m)
        // phi_m by rotation: one sin/cos pair per theta_m
        float cd = cos(dphi), sd = sin(dphi);
        float cp = cos(0.5f * dphi), sp = sin(0.5f * dphi);
        vec3 row = vec3(0.0f);   // the sum over phi_m first: a sum of nodes_phi terms, then of nodes_theta rows
        float row_lobe = 0.0f, row_outside = 0.0f;
        for (uint j = 0u; j < nodes_phi; ++j) {
            vec3 m = vec3(sin_m * cp, sin_m * sp, cos_m);
            float lm = dot(l, m);
            vec3 v = reflect_about(l, m);
            float hz = half_cell * sp;   // how far v.z moves over half of node j's cell
            float cn = cp * cd - sp * sd;
            sp = sp * cd + cp * sd;
            cp = cn;
            if (lm <= 0.0f || v.z <= 0.0f) continue;   // rounding at phi_max
            float g_over_c = masking == FGD_G2           ? 1.0f / (c_masking_l + c * ggx_lambda(v, a))
                             : masking == FGD_SEPARABLE ? ggx_G1(v, a) / c_masking_l
                                                        : 1.0f / c_masking_l;   // G(l, v) / l.z
            float w = g_over_c * lm;
            if (kind == KIND_CONDUCTOR) row += w * fresnel_conductor(lm, cond_eta, cond_k);
            else if (remapped) row += vec3(w * clamp((fresnel_dielectric(lm, eta) - f0) / (1.0f - f0), 0.0f, 1.0f));
            else row += vec3(w * fresnel_dielectric(lm, eta));
            row_lobe += w;
            // the step at the escape cone weighed by the share of node j's cell beyond it, v.z linear across the
            // cell (a sampled step converged as 1 / nodes_phi: 6e-3 off at 32 nodes)
            float t = z_c - v.z;
            row_outside += w * (t >= hz ? 1.0f : (t <= -hz ? 0.0f : 0.5f + 0.5f * t / hz));
        }
        float d = ggx_D(vec3(sin_m, 0.0f, cos_m), a) * sin_m * dtheta * dphi;
        fgd += d * row;
        lobe += d * row_lobe;
        outside += d * row_outside;
    }
    float norm = 2.0f / float(nodes_theta);   // both halves of phi, du
    sums.fgd = fgd * norm;
    sums.lobe = lobe * norm;
    sums.tir = (eta_c >= 1.0f || !(lobe > 0.0f)) ? 1.0f : 1.0f - outside / lobe;
    return sums;
}

GONIO_INLINE vec4 fgd_quadrature(LayerGpu L, float mu, float alpha, bool g2, uint nodes_theta, uint nodes_phi) {
    const FgdSums s = fgd_quadrature_sums(L, mu, alpha, g2 ? FGD_G2 : FGD_SEPARABLE, nodes_theta, nodes_phi);
    return vec4(s.fgd.x, s.fgd.y, s.fgd.z, s.tir);
}
#endif
