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
// at IL_MU_NODES x IL_MU_NODES x IL_PHI_NODES nodes (host/models/stack_tables.cpp, symmetric in l and v by
// construction), less its flat-interface part (1 - F(mu_l)) (1 - F(mu_v)), read trilinearly and that part added back;
// f's body is k_d B / (pi eta^2 (1 - k_d r_i)). Limits: k_d = 0 is Walter's
// dielectric lobe; eta = 1 gives Lambertian microfacets; alpha -> 0 the flat interfaced Lambertian, whose albedo at
// k_d = 1 is F + (1 - F) = 1.
#ifndef GONIO_MODEL_INTERFACED_LAMBERTIAN_GLSL
#define GONIO_MODEL_INTERFACED_LAMBERTIAN_GLSL
#include "models/common.glsl"

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
                b += w * model_stack_table(STACK_TABLE_INTERFACED_BODY + ((i + di) * IL_MU_NODES + (j + dj)) * IL_PHI_NODES +
                                           (k + dk));
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
#endif
