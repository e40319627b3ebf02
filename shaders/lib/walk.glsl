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

// The state of a path between events.
struct Walk {
    vec3 d;           // propagation direction
    vec3 w;           // throughput
    uint k;           // the interface the path is about to hit
    uint reversals;   // direction reversals beneath the top surface
    bool alive;
};

// Event filters: which interfaces one call of walk_event handles (constant at every call site, so the
// branches for the other kinds fold away after inlining).
const uint EVENTS_ANY = 0u;
const uint EVENTS_DIELECTRIC = 1u;   // the dielectric interfaces above an opaque base
const uint EVENTS_BASE = 2u;         // the opaque base

// One scattering event at interface p.k, then the crossing of the medium the path enters, then Russian
// roulette. Does nothing if the path is dead or its interface is not of the kinds `which` names.
GONIO_INLINE void walk_event(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint n, uint which) {
    if (!p.alive) return;
    bool at_base = p.k + 1u == n;
    if (which == EVENTS_DIELECTRIC && at_base) return;
    if (which == EVENTS_BASE && !at_base) return;
    r.events += 1u;
    bool down = p.d.z < 0.0f;
    // Local frame of the event: +z towards the side the path arrives from (mirror z when from below).
    vec3 wi = down ? -p.d : vec3(-p.d.x, -p.d.y, p.d.z);
    vec4 u = rng_next4(rng);
    uint kind = which == EVENTS_DIELECTRIC ? KIND_DIELECTRIC : (which == EVENTS_BASE ? BASE_KIND : walk_kind(p.k));
    // Where the filter pins the interface down, index it with a constant (a uniform load with a per-lane
    // index runs lane by lane on lavapipe).
    uint ki = which == EVENTS_BASE ? LAYER_COUNT - 1u : (which == EVENTS_DIELECTRIC && LAYER_COUNT == 2u ? 0u : p.k);
    LayerGpu L = u_stack.layers[ki];
    Scatter s;
    if (kind == KIND_DIELECTRIC) {
        float eta = down ? L.p0.z : 1.0f / L.p0.z;
        s = sample_dielectric(wi, walk_alpha(ki), eta, u);
    } else if (kind == KIND_CONDUCTOR) {
        s = sample_conductor(wi, walk_alpha(ki), vec3(L.c0.x, L.c0.y, L.c0.z), vec3(L.c1.x, L.c1.y, L.c1.z), u);
    } else {
        s = sample_lambertian(vec3(L.c0.x, L.c0.y, L.c0.z), u);
    }
    r.absorbed += p.w * s.absorbed;
    if (!s.valid) {
        r.lost += p.w * (vec3(1.0f) - s.absorbed);
        r.outcome = OUTCOME_ENDED;
        p.w = vec3(0.0f);
        p.alive = false;
        return;
    }
    r.lost += p.w * (vec3(1.0f) - s.absorbed - s.weight);
    p.w *= s.weight;
    p.d = down ? s.wo : vec3(s.wo.x, s.wo.y, -s.wo.z);
    bool now_down = p.d.z < 0.0f;
    if (now_down != down && !(p.k == 0u && down)) p.reversals += 1u;
    uint medium;
    if (now_down) {
        if (at_base) {                       // left through the bottom of a transmissive stack
            r.outcome = OUTCOME_TRANSMITTED;
            p.alive = false;
            return;
        }
        medium = p.k;
        p.k += 1u;
    } else {
        if (p.k == 0u) {                     // left through the top
            r.outcome = OUTCOME_REFLECTED;
            p.alive = false;
            return;
        }
        medium = p.k - 1u;
        p.k -= 1u;
    }
    // Beer-Lambert through the medium: tau / |cos| per crossing.
    if (walk_absorbs(medium)) {
        vec4 t = (SPECIALISED && LAYER_COUNT == 2u) ? u_stack.layers[0].tau : u_stack.layers[medium].tau;
        vec3 a = exp(-vec3(t.x, t.y, t.z) / max(abs(p.d.z), 1e-30f));
        r.absorbed += p.w * (vec3(1.0f) - a);
        p.w *= a;
    }
    // Russian roulette (unbiased): survive with q = max(w) / RR_THRESHOLD, divide by q.
    float wmax = max(p.w.x, max(p.w.y, p.w.z));
    if (wmax < RR_THRESHOLD) {
        float q = wmax / RR_THRESHOLD;
        if (u.w >= q) {
            r.absorbed += p.w;
            r.outcome = OUTCOME_ENDED;
            p.w = vec3(0.0f);
            p.alive = false;
            return;
        }
        r.absorbed -= p.w * (1.0f / q - 1.0f);
        p.w = p.w / q;
    }
}

// A path in flight: trace_path runs one to the end; simulate.comp interleaves many per invocation.
GONIO_INLINE void walk_begin(OUT(Walk) p, OUT(PathResult) r, float sin_ti, float cos_ti) {
    r.absorbed = vec3(0.0f);
    r.lost = vec3(0.0f);
    r.outcome = OUTCOME_TRUNCATED;
    r.events = 0u;
    r.weight = vec3(0.0f);
    r.dir = vec3(0.0f);
    r.order = 0u;
    p.d = vec3(-sin_ti, 0.0f, -cos_ti);
    p.w = vec3(1.0f);
    p.k = 0u;
    p.reversals = 0u;
    p.alive = true;
}

// One step of the walk. Above an opaque base a step runs the dielectric events and then the base event:
// lanes of a SIMD group that are at different interfaces no longer pay for both kinds on every step (a path
// at the base always leaves it upwards, so on a two-layer stack the two phases alternate exactly).
// Returns false once the path has ended (left, absorbed, lost, or reached max_events).
GONIO_INLINE bool walk_step(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint max_events) {
    uint n = walk_layer_count();
    if (SPECIALISED && BASE_KIND != KIND_DIELECTRIC && LAYER_COUNT > 1u) {
        walk_event(p, r, rng, n, EVENTS_DIELECTRIC);
        if (r.events < max_events) walk_event(p, r, rng, n, EVENTS_BASE);
    } else {
        walk_event(p, r, rng, n, EVENTS_ANY);
    }
    return p.alive && r.events < max_events;
}

GONIO_INLINE void walk_finish(INOUT(Walk) p, INOUT(PathResult) r) {
    r.weight = p.w;
    r.dir = p.d;
    r.order = min(p.reversals, 2u);
}

GONIO_INLINE PathResult trace_path(float sin_ti, float cos_ti, INOUT(Rng) rng, uint max_events) {
    Walk p;
    PathResult r;
    walk_begin(p, r, sin_ti, cos_ti);
    for (uint it = 0u; it < max_events; ++it)
        if (!walk_step(p, r, rng, max_events)) break;
    walk_finish(p, r);
    return r;
}
#endif
