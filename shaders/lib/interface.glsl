// interface.glsl: sampling one scattering event at one interface of the stack, in the interface's local
// frame (z = macro-normal pointing to the side the light arrives from; wi points away from the surface,
// towards where the light came from, wi.z > 0). Single-scattering microfacet interfaces, as in the models
// gonio compares: a sampled direction that ends on the wrong side of the macro-surface has hit the
// microsurface again and its energy is counted as lost ("microfacet loss"), not re-scattered.
#ifndef GONIO_INTERFACE_GLSL
#define GONIO_INTERFACE_GLSL
#include "compat.glsl"
#include "fresnel.glsl"
#include "microsurface.glsl"

// Index-matched interfaces (|eta - 1| below this) are pass-through: there is no interface at all.
const float INDEX_MATCH_EPS = 1e-6f;

struct Scatter {
    vec3 wo;        // sampled direction (local frame), pointing away from the surface on its side
    vec3 weight;    // throughput factor: f cos / pdf
    vec3 absorbed;  // fraction of the arriving throughput absorbed by the event (conductor 1 - F,
                    // lambertian 1 - albedo, dielectric 0); 1 - absorbed - weight is microfacet loss
    bool valid;     // false: single-scattering microfacet loss (wo on the wrong side); weight then is the
                    // throughput the path would have carried, and counts as lost energy
};

GONIO_INLINE vec3 reflect_about(vec3 wi, vec3 m) { return 2.0f * dot(wi, m) * m - wi; }

// Refraction of wi through a microfacet m (wi.m > 0), eta = n_t / n_i, cos_t from refracted_cos().
GONIO_INLINE vec3 refract_through(vec3 wi, vec3 m, float cos_im, float cos_t, float eta) {
    return (cos_im / eta - cos_t) * m - wi / eta;
}

// Dielectric interface, eta = n_t / n_i. Rough (alpha > 0): Walter et al. 2007 BSDF, m sampled from the
// visible normals, reflection chosen with probability F(wi.m), weight G2(wi, wo) / G1(wi), of the microsurface
// `micro` (microsurface.glsl: GGX or Beckmann, height-correlated or separable Smith; the same in every routine here).
// Smooth (alpha == 0): the exact delta interface, reflection with probability F, weight 1.
// u: x, y pick the microfacet, z picks reflection or refraction.
// inv_eta = 1 / eta (the walk has it at hand; multiplications instead of divisions).
// may_be_smooth = false promises alpha > 0 (the smooth-only renormalisation is then left out).
// Written without branches (selects only): lavapipe runs both sides of every branch under a mask anyway, and a
// value assigned in a branch becomes a masked read-modify-write of a stack slot.
GONIO_INLINE Scatter sample_dielectric_inv(vec3 wi, float alpha, uint micro, float eta, float inv_eta,
                                           bool may_be_smooth, vec4 u) {
    Scatter s;
    bool rough = alpha > 0.0f;
    vec3 m = rough ? sample_visible_normal(wi, alpha, micro, u.x, u.y) : vec3(0.0f, 0.0f, 1.0f);
    float cos_im = dot(wi, m);
    float cos_t;
    float F = fresnel_dielectric_cos_t(cos_im, eta, inv_eta * inv_eta, cos_t);
    bool reflect = u.z < F;   // else refract: cos_t >= 0 (0 under TIR, but F == 1 there, so u.z < F)
    vec3 wo = reflect ? reflect_about(wi, m) : (cos_im * inv_eta - cos_t) * m - wi * inv_eta;
    bool valid = reflect ? wo.z > 0.0f : wo.z < 0.0f;
    float weight = rough ? microsurface_G2_over_G1(wi, wo, alpha, micro) : 1.0f;
    if (may_be_smooth) wo = rough ? wo : normalize_unit_scale(wo);
    bool matched = abs(eta - 1.0f) < INDEX_MATCH_EPS;   // no interface
    s.wo = matched ? -wi : wo;
    s.weight = vec3(matched ? 1.0f : weight);
    s.absorbed = vec3(0.0f);
    s.valid = matched || valid;
    return s;
}

// Both branches of a dielectric event, eta = n_t / n_i, in expectation over the choice between them (the walk's
// entry, the exit estimate; trace_book.glsl): m from the visible normals as in sample_dielectric_inv (u: x, y), the
// refracted branch returned (direction, weight (1 - F) G2 / G1 (rough) or 1 - F (smooth); invalid under total
// internal reflection or where the direction is on the wrong side) and the reflected one written to `reflected`
// (direction, weight F G2 / G1 or F; weight 0 where the direction is on the wrong side). The reflected weight is
// also the returned Scatter's `absorbed`: what leaves the refracted path other than by microfacet loss. An
// index-matched interface passes the path on, weight 1, nothing reflected.
GONIO_INLINE Scatter sample_dielectric_branches(vec3 wi, float alpha, uint micro, float eta, float inv_eta,
                                                bool may_be_smooth, vec2 u, OUT(vec4) reflected) {
    Scatter s;
    bool rough = alpha > 0.0f;
    vec3 m = rough ? sample_visible_normal(wi, alpha, micro, u.x, u.y) : vec3(0.0f, 0.0f, 1.0f);
    float cos_im = dot(wi, m);
    float cos_t;
    float F = fresnel_dielectric_cos_t(cos_im, eta, inv_eta * inv_eta, cos_t);
    vec3 wr = rough ? reflect_about(wi, m) : vec3(-wi.x, -wi.y, wi.z);   // smooth: the exact mirror direction
    vec3 wt = (cos_im * inv_eta - cos_t) * m - wi * inv_eta;
    float gr = rough ? microsurface_G2_over_G1(wi, wr, alpha, micro) : 1.0f;
    float gt = rough ? microsurface_G2_over_G1(wi, wt, alpha, micro) : 1.0f;
    if (may_be_smooth) wt = rough ? wt : normalize_unit_scale(wt);
    bool matched = abs(eta - 1.0f) < INDEX_MATCH_EPS;   // no interface
    float r = matched || wr.z <= 0.0f ? 0.0f : F * gr;
    reflected = vec4(wr.x, wr.y, wr.z, r);
    s.wo = matched ? -wi : wt;
    s.weight = vec3(matched ? 1.0f : (1.0f - F) * gt);
    s.absorbed = vec3(r);
    s.valid = matched || (F < 1.0f && wt.z < 0.0f);
    return s;
}

GONIO_INLINE Scatter sample_dielectric(vec3 wi, float alpha, uint micro, float eta, vec4 u) {
    return sample_dielectric_inv(wi, alpha, micro, eta, 1.0f / eta, true, u);
}

// Conductor with complex relative IOR eta + i k: reflection only, weight F(wi.m) G2 / G1 (rough) or F (smooth).
GONIO_INLINE Scatter sample_conductor(vec3 wi, float alpha, uint micro, vec3 eta, vec3 k, vec4 u) {
    Scatter s;
    bool rough = alpha > 0.0f;
    vec3 m = rough ? sample_visible_normal(wi, alpha, micro, u.x, u.y) : vec3(0.0f, 0.0f, 1.0f);
    float cos_im = dot(wi, m);
    s.wo = reflect_about(wi, m);
    vec3 F = fresnel_conductor(cos_im, eta, k);
    s.absorbed = vec3(1.0f) - F;
    s.weight = rough ? F * microsurface_G2_over_G1(wi, s.wo, alpha, micro) : F;
    s.valid = s.wo.z > 0.0f;
    return s;
}

// Lambertian reflector: cosine-weighted direction, weight = albedo.
GONIO_INLINE Scatter sample_lambertian(vec3 albedo, vec4 u) {
    Scatter s;
    s.wo = sample_cosine_hemisphere(u.x, u.y);
    s.weight = albedo;
    s.absorbed = vec3(1.0f) - albedo;
    s.valid = true;
    return s;
}

// Lambertian reflector for the Lambertian series (walk.glsl): the direction from a mixture of the cosine density
// within a cone around the normal (probability emit.y; sin^2 of the half-angle emit.x, the coat's escape cone
// widened by its roughness) and over the whole hemisphere (1 - emit.y); weight = albedo cos / (pi pdf) (emit.z
// inside the cone, emit.w outside). pdf = cos/pi (emit.y / emit.x [sin^2 < emit.x] + 1 - emit.y): never 0, so
// unbiased whatever the cone, and with emit.y = 1 exact for a smooth coat (nothing leaves it from outside the
// cone). u: x, y pick the direction, z picks the cone or the hemisphere.
GONIO_INLINE Scatter sample_lambertian_series(vec3 albedo, vec4 emit, vec4 u) {
    Scatter s;
    float sin2 = u.x * (u.z < emit.y ? emit.x : 1.0f);     // Malley's method: sin^2 theta uniform in [0, s_max)
    float r = sqrt(sin2);
    float phi = 2.0f * PI * u.y;
    s.wo = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0f, 1.0f - sin2)));
    s.weight = albedo * (sin2 < emit.x ? emit.z : emit.w);
    s.absorbed = vec3(1.0f) - albedo;
    s.valid = true;
    return s;
}

// ---- densities of the sampling routines above (used by the chi-square tests) -----------------------
// Solid-angle density of the direction returned by sample_dielectric (valid or not), rough case.
// Reflection: p = F(wi.m) D_wi(m) / (4 wi.m), m = normalize(wi + wo).
// Transmission: p = (1 - F(wi.m)) D_wi(m) eta^2 |wo.m| / (wi.m + eta wo.m)^2, m = -normalize(wi + eta wo)
// (Walter et al. 2007, eqs. 14 and 17, with the visible-normal density in place of D |m.n|).
GONIO_INLINE float pdf_dielectric(vec3 wi, vec3 wo, float alpha, uint micro, float eta) {
    // reflection lobe
    float p = 0.0f;
    vec3 hr = normalize(wi + wo);
    if (hr.z < 0.0f) hr = -hr;
    float cr = dot(wi, hr);
    if (cr > 0.0f && dot(wo, hr) > 0.0f)
        p += fresnel_dielectric(cr, eta) * visible_normal_pdf(wi, hr, alpha, micro) / (4.0f * cr);
    // transmission lobe
    vec3 ht = -normalize(wi + eta * wo);
    if (ht.z < 0.0f) ht = -ht;
    float ci = dot(wi, ht);
    float co = dot(wo, ht);
    if (ci > 0.0f && co < 0.0f) {
        float den = ci + eta * co;
        p += (1.0f - fresnel_dielectric(ci, eta)) * visible_normal_pdf(wi, ht, alpha, micro)
             * eta * eta * abs(co) / (den * den);
    }
    return p;
}

// Density of the direction returned by sample_conductor (valid or not), rough case.
GONIO_INLINE float pdf_conductor(vec3 wi, vec3 wo, float alpha, uint micro) {
    vec3 hr = normalize(wi + wo);
    if (hr.z < 0.0f) hr = -hr;
    float cr = dot(wi, hr);
    if (cr <= 0.0f || dot(wo, hr) <= 0.0f) return 0.0f;
    return visible_normal_pdf(wi, hr, alpha, micro) / (4.0f * cr);
}
// Density of the direction returned by sample_lambertian_series.
GONIO_INLINE float pdf_lambertian_series(vec3 wo, vec4 emit) {
    if (wo.z <= 0.0f) return 0.0f;
    float sin2 = 1.0f - wo.z * wo.z;
    return wo.z / PI * ((sin2 < emit.x ? emit.y / emit.x : 0.0f) + 1.0f - emit.y);
}
#endif
