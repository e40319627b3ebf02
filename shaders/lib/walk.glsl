// walk.glsl: one light path through the layer stack (the reference estimator).
//
// Conventions (docs/PHYSICS.md): global frame z = stack normal, exterior above. The path starts at the light
// with incident direction l = (sin theta_i, 0, cos theta_i) (pointing away from the surface), i.e. it travels
// along -l. It carries an RGB throughput w (starting at 1) and ends by leaving the stack through the top
// (reflected) or the bottom of a transmissive stack (transmitted), by being absorbed or lost, by Russian
// roulette, or at the event cap (truncated). Every change of w is booked: absorbed + lost + truncated +
// leaving = 1 per path (Russian roulette books its gain/loss as absorption, zero on average).
//
// Needs, defined by the includer (GLSL: specialisation constants and a uniform block; C++: members):
//   SPECIALISED (bool), LAYER_COUNT, BASE_KIND, ROUGH_MASK, ABSORB_MASK (uint), u_stack.layers[], u_stack.info.x
#ifndef GONIO_WALK_GLSL
#define GONIO_WALK_GLSL

struct PathResult {
    vec3 weight;      // throughput leaving the stack (OUTCOME_REFLECTED / TRANSMITTED) or truncated
    vec3 absorbed;    // booked absorption (media, base, conductor; Russian roulette balance)
    vec3 lost;        // single-scattering microfacet loss (masking-shadowing, below-horizon samples)
    vec3 dir;         // exit direction (global frame, away from the stack)
    uint outcome;
    uint order;       // path class: number of direction reversals beneath the top surface, capped at 2
    uint events;      // scattering events of the path
};

GONIO_INLINE uint walk_layer_count() { return SPECIALISED ? LAYER_COUNT : uint(u_stack.info.x); }

GONIO_INLINE uint walk_kind(uint k) {
    if (SPECIALISED) return k + 1u == LAYER_COUNT ? BASE_KIND : KIND_DIELECTRIC;
    return uint(u_stack.layers[k].p0.x);
}

GONIO_INLINE float walk_alpha(uint k) {
    if (SPECIALISED && ((ROUGH_MASK >> k) & 1u) == 0u) return 0.0f;
    return u_stack.layers[k].p0.y;
}

GONIO_INLINE bool walk_absorbs(uint m) {
    if (SPECIALISED) return ((ABSORB_MASK >> m) & 1u) != 0u;
    vec4 t = u_stack.layers[m].tau;
    return t.x > 0.0f || t.y > 0.0f || t.z > 0.0f;
}

GONIO_INLINE PathResult trace_path(float sin_ti, float cos_ti, INOUT(Rng) rng, uint max_events) {
    PathResult r;
    r.absorbed = vec3(0.0f);
    r.lost = vec3(0.0f);
    r.outcome = OUTCOME_TRUNCATED;
    r.order = 0u;
    vec3 d = vec3(-sin_ti, 0.0f, -cos_ti);   // propagation direction
    vec3 w = vec3(1.0f);
    uint n = walk_layer_count();
    uint k = 0u;                              // the interface the path is about to hit
    uint reversals = 0u;
    r.events = 0u;
    for (uint ev = 0u; ev < max_events; ++ev) {
        r.events = ev + 1u;
        bool down = d.z < 0.0f;
        // Local frame of the event: +z towards the side the path arrives from (mirror z when from below).
        vec3 wi = down ? -d : vec3(-d.x, -d.y, d.z);
        vec4 u = rng_next4(rng);
        uint kind = walk_kind(k);
        LayerGpu L = u_stack.layers[k];
        Scatter s;
        if (kind == KIND_DIELECTRIC) {
            float eta = down ? L.p0.z : 1.0f / L.p0.z;
            s = sample_dielectric(wi, walk_alpha(k), eta, u);
        } else if (kind == KIND_CONDUCTOR) {
            s = sample_conductor(wi, walk_alpha(k), vec3(L.c0.x, L.c0.y, L.c0.z), vec3(L.c1.x, L.c1.y, L.c1.z), u);
        } else {
            s = sample_lambertian(vec3(L.c0.x, L.c0.y, L.c0.z), u);
        }
        r.absorbed += w * s.absorbed;
        if (!s.valid) {
            r.lost += w * (vec3(1.0f) - s.absorbed);
            r.outcome = OUTCOME_ENDED;
            r.weight = vec3(0.0f);
            r.dir = d;
            r.order = min(reversals, 2u);
            return r;
        }
        r.lost += w * (vec3(1.0f) - s.absorbed - s.weight);
        w *= s.weight;
        d = down ? s.wo : vec3(s.wo.x, s.wo.y, -s.wo.z);
        bool now_down = d.z < 0.0f;
        if (now_down != down && !(k == 0u && down)) reversals += 1u;
        uint medium;
        if (now_down) {
            if (k + 1u == n) {                 // left through the bottom of a transmissive stack
                r.outcome = OUTCOME_TRANSMITTED;
                break;
            }
            medium = k;
            k += 1u;
        } else {
            if (k == 0u) {                     // left through the top
                r.outcome = OUTCOME_REFLECTED;
                break;
            }
            medium = k - 1u;
            k -= 1u;
        }
        // Beer-Lambert through the medium: tau / |cos| per crossing.
        if (walk_absorbs(medium)) {
            vec4 t = u_stack.layers[medium].tau;
            vec3 a = exp(-vec3(t.x, t.y, t.z) / max(abs(d.z), 1e-30f));
            r.absorbed += w * (vec3(1.0f) - a);
            w *= a;
        }
        // Russian roulette (unbiased): survive with q = max(w) / RR_THRESHOLD, divide by q.
        float wmax = max(w.x, max(w.y, w.z));
        if (wmax < RR_THRESHOLD) {
            float q = wmax / RR_THRESHOLD;
            if (u.w >= q) {
                r.absorbed += w;
                r.outcome = OUTCOME_ENDED;
                r.weight = vec3(0.0f);
                r.dir = d;
                r.order = min(reversals, 2u);
                return r;
            }
            r.absorbed -= w * (1.0f / q - 1.0f);
            w = w / q;
        }
    }
    r.weight = w;
    r.dir = d;
    r.order = min(reversals, 2u);
    return r;
}
#endif
