// gonio-model: interfaced-lambertian
// citation: Meneveaux, Bringier, Tauzia, Ribardiere, Simonot 2018, "Rendering rough opaque materials with interfaced
//   Lambertian microfacets", IEEE TVCG 24(3) 1368 (and its preprint hal-01246612); as its public implementation
//   computes it (byzin/Nanairo @23fb6dee, source/NanairoCore/Material/SurfaceModel/Surface/layered_diffuse.cpp,
//   microfacet-inl.hpp, microfacet_ggx.cpp: the authors' plugin was not found); the flat interfaced Lambertian of
//   Simonot 2009 and Elias et al. 2001 on every microfacet
// family: production
// summary: microfacets each a flat interfaced Lambertian (a smooth dielectric on a Lambertian): their specular lobe
//   F(l.h) D G1 G1 / (4 mu_l mu_v), and their body rho / (pi eta^2 (1 - rho r_i)) (1 - F(l.m)) (1 - F(v.m))
//   integrated over the microfacets, r_i the flat interface's internal hemispherical reflectance; the physics behind
//   OpenPBR's darkening
// stacks: one colourless dielectric coat (relative IOR at least 1) over a Lambertian base
// mapping: the binder's relative index n = n_coat / n_exterior, the interface's roughness alpha = alpha_coat (GGX),
//   the body's albedo k_d = the Lambertian's albedo
// artist-parameters: coat-over-lambertian = n, alpha, k_d (colour)
// represents: coat-over-lambertian
// reciprocal: yes
// energy-conserving: yes
// plan: coat
// table: interfaced-body 20692
// tables: interfaced-body
// refuses: scattering-medium = {id} has no medium ({layer}): the interface lies on the Lambertian
// refuses: absorbing-medium = {id} has no medium between the interface and the Lambertian ({layer}): the binder's
//   colour is its albedo k_d
// refuses: transmissive = {id} models reflection only (a BRDF); this stack is transmissive (its last layer is a
//   dielectric)
// refuses: not-two-layers = {id} is one interface over one Lambertian; this stack has {layers} layers
// refuses: base-not-lambertian = {id} is an interface over a Lambertian body, not over a {base}
// refuses: coat-ior-below-1 = {id}: the binder is denser than the medium above it (its r_i is the flat interface's
//   internal reflectance); this coat's IOR relative to the exterior is {coat_eta}
//
// models/builtin/15-interfaced-lambertian.glsl: `interfaced-lambertian`. Each microfacet of normal m is a flat
// interfaced Lambertian: a specular Dirac F(l.m) about m and the body
//   f_m(l, v) = k_d (1 - F(l.m, eta)) (1 - F(v.m, eta)) / (pi eta^2 (1 - k_d r_i)),   r_i = 1 - (1 - r_e) / eta^2,
// r_e = 2 int_0^1 F(mu, eta) mu dmu (the cosine-weighted Fresnel: the light inside the binder, Lambertian, that the
// flat interface sends back, TIR included; Nanairo calcRe, layered_diffuse-inl.hpp). Over GGX microfacets of alpha,
// with the separable Smith G1(l) G1(v) (microfacet-inl.hpp):
//   f = F(l.h) D(h) G1(l) G1(v) / (4 mu_l mu_v) + int over m of f_m (l.m)+ (v.m)+ / (mu_l mu_v) D(m) G1(l) G1(v) dm.
// Nanairo estimates the body by one visible normal m of l per evaluation, f_m G1(v) (v.m)+ / mu_v; gonio integrates
// the same mean over the visible normals of l deterministically, once per stack: a table of
//   B(mu_l, mu_v, phi) = the mean over m ~ D_l of (1 - F(l.m)) (1 - F(v.m)) (v.m)+ G1(v) / mu_v
// at IL_MU_NODES x IL_MU_NODES x IL_PHI_NODES nodes (the set this file declares, interfaced_tables on the host,
// symmetric in l and v by construction), less its flat-interface part (1 - F(mu_l)) (1 - F(mu_v)), read trilinearly
// and that part added back; f's body is k_d B / (pi eta^2 (1 - k_d r_i)). Limits: k_d = 0 is Walter's dielectric
// lobe; eta = 1 gives Lambertian microfacets; alpha -> 0 the flat interfaced Lambertian, whose albedo at k_d = 1 is
// F + (1 - F) = 1.
#ifndef GONIO_MODEL_INTERFACED_LAMBERTIAN_GLSL
#define GONIO_MODEL_INTERFACED_LAMBERTIAN_GLSL
#include "models/common.glsl"

// The set this file declares (`table: interfaced-body`): the flat interface's internal reflectance r_i, then the
// body's mean over visible normals B(mu_l, mu_v, phi) less its flat part at IL_MU_NODES^2 x IL_PHI_NODES nodes,
// [mu_l][mu_v][phi]
const uint IL_MU_NODES = 33u;
const uint IL_PHI_NODES = 19u;
const uint STACK_TABLE_INTERFACED_RI = STACK_TABLE_INTERFACED_BODY;
const uint STACK_TABLE_INTERFACED_BODY_MEAN = STACK_TABLE_INTERFACED_RI + 1u;
#ifdef __cplusplus
static_assert(1u + IL_MU_NODES * IL_MU_NODES * IL_PHI_NODES == STACK_TABLE_INTERFACED_BODY_FLOATS,
              "the set's `table:` size");
#endif
// The table's nodes: mu = i / (IL_MU_NODES - 1) (node 0 tabulated at INTERFACED_MU_MIN), the azimuth between l and v
// phi = k pi / (IL_PHI_NODES - 1)
const float INTERFACED_MU_MIN = 1e-3f;
GONIO_INLINE float interfaced_mu_node(uint i) {
    return i == 0u ? INTERFACED_MU_MIN : float(i) / float(IL_MU_NODES - 1u);
}
GONIO_INLINE float interfaced_phi_node(uint k) { return float(k) * PI / float(IL_PHI_NODES - 1u); }

// The body's integrand at one visible normal m of a: (1 - F(a.m)) (1 - F(b.m)) (b.m)+ G1(b) / b.z
GONIO_INLINE float interfaced_body_integrand(vec3 a, vec3 b, vec3 m, float eta, float alpha) {
    const float bm = dot(b, m);
    if (bm <= 0.0f) return 0.0f;
    return (1.0f - fresnel_dielectric(max(dot(a, m), 0.0f), eta)) * (1.0f - fresnel_dielectric(bm, eta)) * bm *
           ggx_G1(b, alpha) / b.z;
}

// The body's flat-interface part (1 - F(mu_l)) (1 - F(mu_v)), what B is for a smooth interface; the table holds B less
// it, so that its trilinear reading is exact in that limit (the flat part read trilinearly was 0.5% off at 85
// degrees). The cosines taken at INTERFACED_MU_MIN or above, as node 0 is: below, the float Fresnel of an index-matched
// interface is 1 (1 - mu^2 rounds to 1), which the table's node does not see
GONIO_INLINE float interfaced_flat_body(float mu_l, float mu_v, float eta) {
    return (1.0f - fresnel_dielectric(max(mu_l, INTERFACED_MU_MIN), eta)) *
           (1.0f - fresnel_dielectric(max(mu_v, INTERFACED_MU_MIN), eta));
}

// B(mu_l, mu_v, phi): the flat part plus the per-stack table's rest, trilinear in (mu_l, mu_v, phi) over its nodes
GONIO_INLINE float interfaced_body(vec3 l, vec3 v, float eta) {
    const float sl = length(vec2(l.x, l.y)), sv = length(vec2(v.x, v.y));
    const float c = sl > 0.0f && sv > 0.0f ? clamp((l.x * v.x + l.y * v.y) / (sl * sv), -1.0f, 1.0f) : 1.0f;
    const float x = clamp(l.z, 0.0f, 1.0f) * float(IL_MU_NODES - 1u), y = clamp(v.z, 0.0f, 1.0f) * float(IL_MU_NODES - 1u);
    const float z = acos(c) / PI * float(IL_PHI_NODES - 1u);
    const uint i = min(uint(x), IL_MU_NODES - 2u), j = min(uint(y), IL_MU_NODES - 2u), k = min(uint(z), IL_PHI_NODES - 2u);
    const float tx = x - float(i), ty = y - float(j), tz = z - float(k);
    float b = 0.0f;
    for (uint di = 0u; di < 2u; ++di)
        for (uint dj = 0u; dj < 2u; ++dj)
            for (uint dk = 0u; dk < 2u; ++dk) {
                const float w = (di == 0u ? 1.0f - tx : tx) * (dj == 0u ? 1.0f - ty : ty) * (dk == 0u ? 1.0f - tz : tz);
                b += w * model_stack_table(STACK_TABLE_INTERFACED_BODY_MEAN +
                                           ((i + di) * IL_MU_NODES + (j + dj)) * IL_PHI_NODES + (k + dk));
            }
    return interfaced_flat_body(l.z, v.z, eta) + b;
}

GONIO_INLINE vec3 model_interfaced_lambertian(CoatParams p, uint terms, vec3 l, vec3 v) {
    vec3 f = vec3(0.0f);
    if (l.z <= 0.0f || v.z <= 0.0f) return f;
    if (p.base_kind != KIND_LAMBERTIAN) return vec3(model_nan());
    if ((terms & TERM_TOP) != 0u) {
        const vec3 h = normalize(l + v);
        f += vec3(fresnel_dielectric(dot(l, h), p.eta) * ggx_D(h, p.alpha0) * ggx_G2_separable(l, v, p.alpha0) /
                  (4.0f * l.z * v.z));
    }
    if ((terms & TERM_BASE) != 0u) {
        const float r_i = model_stack_table(STACK_TABLE_INTERFACED_RI);
        f += p.base_c0 / (PI * p.eta * p.eta * (vec3(1.0f) - p.base_c0 * r_i)) * interfaced_body(l, v, p.eta);
    }
    return f;
}

// The mapping (`mapping:`; `artist-parameters:` names the values in this order): Meneveaux et al.'s parameters
GONIO_INLINE void interfaced_lambertian_artist_parameters(CoatParams p, vec3 diffuse, INOUT(ArtistValues) a) {
    artist_value(a, p.eta);       // n: the binder's index relative to the exterior
    artist_value(a, p.alpha0);    // alpha (GGX)
    artist_value(a, p.base_c0);   // k_d
}
#define GONIO_MODEL_ARTIST_PARAMETERS(p, diffuse, a) interfaced_lambertian_artist_parameters(p, diffuse, a)

#ifdef __cplusplus
// interfaced-body on the host (model_twin.h). The body table's quadrature over the visible normals
// (sample_ggx_visible_normal's square: the periodic azimuth by the midpoint rule, the cap's height by Gauss-Legendre):
// 64 x 32 nodes are within 1e-4 of the body (4.3e-4 at alpha 0.8) where the midpoint rule on 32 x 32 was 9e-3 off
// (at alpha 0.05; against 512 x 512 midpoint nodes)
const uint INTERFACED_AZIMUTH_NODES = 64u;
const uint INTERFACED_CAP_NODES = 32u;
// The body's mean over the visible normals of a, on n_az x n_cap nodes
GONIO_INLINE double interfaced_body_quadrature(vec3 a, vec3 b, float eta, float alpha, uint n_az, uint n_cap) {
    double sum = 0.0;
    for (uint j = 0u; j < n_cap; ++j) {
        const float cap = float(table_gauss_legendre_node(n_cap, j));
        double row = 0.0;
        for (uint i = 0u; i < n_az; ++i)
            row += interfaced_body_integrand(
                a, b, sample_ggx_visible_normal(a, alpha, (float(i) + 0.5f) / float(n_az), cap), eta, alpha);
        sum += table_gauss_legendre_weight(n_cap, j) * row / double(n_az);
    }
    return sum;
}
// The body's mean over visible normals B at the table's node (i, j, k), over the visible normals of the more grazing
// of the two directions (its masking's edge is then inside the cap's map)
GONIO_INLINE float interfaced_body_node(float eta, float alpha, uint i, uint j, uint k, uint n_az, uint n_cap) {
    const float mi = interfaced_mu_node(i), mj = interfaced_mu_node(j), phi = interfaced_phi_node(k);
    const vec3 a = vec3(sqrt(1.0f - mi * mi), 0.0f, mi);
    const float sj = sqrt(1.0f - mj * mj);
    const vec3 b = vec3(sj * cos(phi), sj * sin(phi), mj);
    return float(i <= j ? interfaced_body_quadrature(a, b, eta, alpha, n_az, n_cap)
                        : interfaced_body_quadrature(b, a, eta, alpha, n_az, n_cap));
}
// The flat interface's internal hemispherical reflectance r_i = 1 - (1 - r_e) / eta^2, r_e = 2 int F(mu, eta) mu dmu
GONIO_INLINE float interfaced_internal_reflectance(float eta) {
    const double r_e = table_cosine_average(TABLE_MEAN_FRESNEL, eta, 0.0f, FGD_G2);
    return float(1.0 - (1.0 - r_e) / (double(eta) * eta));
}
// r_i, and B less its flat part at every node, each node pair once (symmetric by construction)
GONIO_INLINE void interfaced_tables(StackGpu s, uint sets) {
    if ((sets & STACK_TABLES_INTERFACED_BODY) == 0u || table_stack_shape(s) != TABLE_SHAPE_TWO_LAYER_OPAQUE) return;
    const CoatParams p = coat_params(s.layers[0], s.layers[1]);
    model_stack_table_store(STACK_TABLE_INTERFACED_RI, interfaced_internal_reflectance(p.eta));
    for (uint i = 0u; i < IL_MU_NODES; ++i)
        for (uint j = i; j < IL_MU_NODES; ++j)
            for (uint k = 0u; k < IL_PHI_NODES; ++k) {
                const float b =
                    interfaced_body_node(p.eta, p.alpha0, i, j, k, INTERFACED_AZIMUTH_NODES, INTERFACED_CAP_NODES) -
                    interfaced_flat_body(interfaced_mu_node(i), interfaced_mu_node(j), p.eta);
                model_stack_table_store(STACK_TABLE_INTERFACED_BODY_MEAN + (i * IL_MU_NODES + j) * IL_PHI_NODES + k, b);
                model_stack_table_store(STACK_TABLE_INTERFACED_BODY_MEAN + (j * IL_MU_NODES + i) * IL_PHI_NODES + k, b);
            }
}
#define GONIO_MODEL_TABLES(s, sets) interfaced_tables(s, sets)
#endif
#endif
