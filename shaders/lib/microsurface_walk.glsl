// microsurface_walk.glsl: multiple scattering on a rough interface's microsurface (`microfacets = "multiple"`): the
// random walk of Heitz, Hanika, d'Eon and Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the Smith
// Model" (Sec. 4 to 6; their supplemental code, MicrosurfaceScattering.cpp: Microsurface::sampleHeight,
// MicrosurfaceDielectric::sample and samplePhaseFunction), sampled, never evaluated: a gonio-photometer only bins.
//
// The microsurface is the Smith one (uncorrelated heights and slopes) with the uniform height distribution of their
// code, P1 = 1/2 on [-1, 1], its CDF C1(h) = (h + 1) / 2; the result does not depend on the height distribution (their
// Sec. 4.2). The walk keeps c = C1(h) of the height where the path last met the microsurface (1 above it). Along a
// direction w with Smith Lambda L = Lambda(w) of w seen from its side (|w.z|; microsurface.glsl):
//   going down (w.z < 0), it meets the microsurface again for sure, at c' = c (1 - U)^(1 / (1 + L));
//   going up, it leaves with probability G1(w, h) = c^L, else meets it at c' = c (1 - U)^(-1 / L)
// (their sampleHeight, with Lambda(-w) = -1 - Lambda(w)). Each meeting is a microfacet m from the visible normals of
// the arriving direction -w (below the horizon after a path going up is met again: D_-w(m) is max(0, -w.m) D(m) /
// its projected area there too, and both samplers take such directions) and one event there: a conductor reflects
// with weight F(wi.m); a dielectric reflects with probability F(wi.m), else refracts and the walk goes on from the
// other side of the microsurface: its frame mirrored in z, its height h -> -h (c -> 1 - c). The first meeting uses
// the event's u.x, u.y (the facet) and u.z (the choice) as the single-scattering samplers do (interface.glsl); its
// height and everything after come from the event's own stream (microsurface_stream). Its first meeting, weighted by
// the chance to leave after it, is the single-scattering BSDF with height-correlated G2 (Heitz 2016, Sec. 5.2).
//
// The walk stops after MICROSURFACE_MAX_MEETINGS meetings: a path still on the microsurface then is invalid (Scatter
// valid false) and its throughput is booked as lost (walk.glsl), never dropped unrecorded.
#ifndef GONIO_MICROSURFACE_WALK_GLSL
#define GONIO_MICROSURFACE_WALK_GLSL
#include "compat.glsl"
#include "rng.glsl"
#include "interface.glsl"

const uint MICROSURFACE_MAX_MEETINGS = 64u;

// The random stream of the microsurface walk at the path's current event: the path's key with its seed word mixed
// with the event counter (a path's own stream never has this word; distinct events, distinct streams), counted from 0.
GONIO_INLINE Rng microsurface_stream(Rng path) {
    Rng m;
    m.key = uvec4(path.key.x, path.key.y, path.key.z ^ 0x5bd1e995u ^ (path.key.w * 0x9e3779b9u), 0u);
    return m;
}

// The next height of a path leaving its last meeting at c = C1(h) along w (w.z < 0 down, else up), with the
// uniform number u: c' in (0, 1) where it meets the microsurface again, or 2 where it leaves (see above).
GONIO_INLINE float microsurface_next_height(vec3 w, float c, float alpha, uint micro, float u) {
    float L = microsurface_lambda(w, alpha, micro);   // Lambda of w seen from its side: 0 along the normal
    float lu = log2(1.0f - u), lc = log2(c);          // 1 - u in (0, 1]: lu <= 0; lc <= 0
    bool up = w.z > 0.0f;
    bool leaves = up && (lc >= 0.0f || lu <= L * lc);   // 1 - u <= c^L (L = 0: always; at the horizon: never)
    float next = c * exp2(up ? -lu / L : lu / (1.0f + L));
    return leaves ? 2.0f : max(next, 1e-30f);   // kept above 0: c = 0 would never leave (log2 0)
}

// Heitz 2016's walk from wi (wi.z > 0, local frame of the arriving side; alpha > 0), `micro` its statistics
// (MICROSURFACE_BECKMANN or GGX; height-correlated by construction). dielectric: eta = n_t / n_i, inv_eta = 1 / eta,
// non-absorbing (weight 1); else a conductor of complex relative IOR c_eta + i c_k (weight the product of F). The
// Scatter's wo is on the arriving side (reflected) or the other (wo.z < 0, transmitted); absorbed is the conductor's
// 1 - weight; invalid after max_meetings meetings on the microsurface (the walk: MICROSURFACE_MAX_MEETINGS; a test of
// the first meeting: 1), wo then the direction it was on.
GONIO_INLINE Scatter sample_microsurface_walk(vec3 wi, float alpha, uint micro, bool dielectric, float eta,
                                              float inv_eta, vec3 c_eta, vec3 c_k, vec4 u, Rng stream,
                                              uint max_meetings) {
    vec3 w = -wi;        // direction of travel, in the frame of the side the path is on (+z: that side)
    float c = 1.0f;      // C1 of the height of the last meeting: above the microsurface
    bool arriving_side = true;
    vec3 weight = vec3(1.0f);
    vec4 v = rng_next4(stream);
    float uh = v.x;                       // the first meeting's height
    vec3 uf = vec3(u.x, u.y, u.z);        // its facet and choice, the single-scattering samplers' numbers
    bool left = false;
    for (uint meetings = 0u; meetings <= max_meetings; ++meetings) {
        float h = microsurface_next_height(w, c, alpha, micro, uh);
        left = h > 1.0f;
        if (left || meetings == max_meetings) break;
        c = h;
        vec3 wl = -w;   // towards where the light came from (below the horizon after a path going up)
        vec3 m = sample_visible_normal(wl, alpha, micro, uf.x, uf.y);
        float cos_im = dot(wl, m);
        float e = arriving_side ? eta : inv_eta, inv_e = arriving_side ? inv_eta : eta;
        float cos_t = 0.0f;
        float F = dielectric ? fresnel_dielectric_cos_t(cos_im, e, inv_e * inv_e, cos_t) : 1.0f;
        bool refracts = dielectric && uf.z >= F;   // F == 1 under total internal reflection
        vec3 t = (cos_im * inv_e - cos_t) * m - wl * inv_e;
        vec3 r = reflect_about(wl, m);
        weight = dielectric ? weight : weight * fresnel_conductor(cos_im, c_eta, c_k);
        // refracted: the other side's frame (z mirrored) and height (h -> -h)
        w = refracts ? vec3(t.x, t.y, -t.z) : r;
        c = refracts ? max(1.0f - c, 1e-30f) : c;
        arriving_side = refracts ? !arriving_side : arriving_side;
        v = rng_next4(stream);
        uh = v.w;
        uf = vec3(v.x, v.y, v.z);
    }
    Scatter s;
    s.wo = arriving_side ? w : vec3(w.x, w.y, -w.z);
    s.weight = weight;
    s.absorbed = dielectric ? vec3(0.0f) : vec3(1.0f) - weight;
    s.valid = left;
    bool matched = dielectric && abs(eta - 1.0f) < INDEX_MATCH_EPS;   // no interface
    s.wo = matched ? -wi : s.wo;
    s.weight = matched ? vec3(1.0f) : s.weight;
    s.valid = matched || s.valid;
    return s;
}
#endif
