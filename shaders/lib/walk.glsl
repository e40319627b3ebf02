// walk.glsl: one light path through the layer stack (the reference estimator).
//
// Conventions (docs/PHYSICS.md): global frame z = stack normal, exterior above. The path starts at the light
// with incident direction l = (sin theta_i cos phi_i, sin theta_i sin phi_i, cos theta_i) (pointing away from the
// surface; bins.glsl incident_direction), i.e. it travels along -l. It carries an RGB throughput w (starting at 1)
// and ends by leaving the stack through the top (reflected) or the bottom of a transmissive stack (transmitted), by
// being absorbed or lost, by Russian roulette, or at the event cap (truncated). Every change of w is booked:
// absorbed + lost + truncated + leaving = 1 per path (Russian roulette books its gain/loss as absorption, zero on
// average).
//
// The Lambertian series (SERIES, a dielectric coat over a Lambertian base; docs/PHYSICS.md): light leaving a
// Lambertian base has forgotten where it came from, so every trip base -> coat -> base is alike and their sum is a
// geometric series. With SERIES the walk traces the first trip only: at the base it books the expected microfacet
// loss of all trips (u_stack.series.lost) and samples the direction from sample_lambertian_series; at the coat,
// from below, a path that leaves carries its weight times S = 1 / (1 - albedo r) (u_stack.series.gain) and one that
// is reflected ends. Unbiased, exactly (r is computed by quadrature, lambertian_series.cpp), three events at most.
//
// Scattering media (docs/PHYSICS.md, "Media"): a path that crosses an interface into a medium that scatters is in
// the medium (Walk.in_medium) until a free flight takes it to one of the medium's two interfaces; each collision on
// the way is a scattering event (the single-scattering albedo, a Henyey-Greenstein direction or a specular
// microflake's, Russian roulette). The medium then replaces Beer-Lambert: its optical depth is the extinction
// sigma_t d, times the flakes' projected area sigma(d) in a microflake medium (medium.glsl).
//
// Needs, defined by the includer (GLSL: specialisation constants and a uniform block; C++: members):
//   SPECIALISED, SERIES (bool), LAYER_COUNT, BASE_KIND, ROUGH_MASK, ABSORB_MASK, SCATTER_MASK, MICROSURFACE_MASK,
//   MULTIPLE_MASK, MICROFLAKE_MASK (uint), u_stack.layers[],
//   u_stack.info, u_stack.series; and, where the includer has a baked stack (GONIO_BAKED_STACK defined), BAKED_STACK
//   (bool) and baked_layer(k), baked_series(), baked_sides(), which then stand in for u_stack (walk_layer,
//   walk_series, walk_sides).
#ifndef GONIO_WALK_GLSL
#define GONIO_WALK_GLSL

struct PathResult {
    vec3 weight;      // throughput leaving the stack (OUTCOME_REFLECTED / TRANSMITTED) or truncated
    vec3 absorbed;    // booked absorption (media, base, conductor; Russian roulette balance): 1 - lost - weight
    vec3 lost;        // single-scattering microfacet loss (masking-shadowing, below-horizon samples)
    vec3 dir;         // exit direction (global frame, away from the stack)
    uint outcome;
    uint order;       // path class: number of direction reversals beneath the top surface, capped at 2
    uint events;      // scattering events of the path
};

// The stack's parameters. Where the includer has a baked stack (BAKED_STACK: a specialised walk of at most two
// layers; simulate.comp's specialisation constants, stack_constants.glsl, or simulate_batch.comp's copies read once
// per invocation), from there: on lavapipe a uniform read is an 8-lane gather and a storage-buffer read a loop over
// the lanes, on every event. Else the uniform block.
#ifdef GONIO_BAKED_STACK
GONIO_INLINE LayerGpu walk_layer(uint k) {
    if (BAKED_STACK) return baked_layer(k);
    return u_stack.layers[k];
}
GONIO_INLINE SeriesGpu walk_series() {
    if (BAKED_STACK) return baked_series();
    return u_stack.series;
}
GONIO_INLINE uint walk_sides() { return BAKED_STACK ? baked_sides() : stack_sides(u_stack.info); }
#else
GONIO_INLINE LayerGpu walk_layer(uint k) { return u_stack.layers[k]; }
GONIO_INLINE SeriesGpu walk_series() { return u_stack.series; }
GONIO_INLINE uint walk_sides() { return stack_sides(u_stack.info); }
#endif

GONIO_INLINE uint walk_layer_count() { return SPECIALISED ? LAYER_COUNT : stack_layer_count(u_stack.info); }

GONIO_INLINE uint walk_kind(uint k) {
    if (SPECIALISED) return k + 1u == LAYER_COUNT ? BASE_KIND : KIND_DIELECTRIC;
    return layer_kind(walk_layer(k));
}

GONIO_INLINE float walk_alpha(uint k) {
    if (SPECIALISED && ((ROUGH_MASK >> k) & 1u) == 0u) return 0.0f;
    return layer_alpha(walk_layer(k));
}

// Interface k's microsurface (microsurface.glsl MICROSURFACE_*): 0, GGX with height-correlated Smith, and its code
// alone, on every stack that does not set `distribution` or `shadowing` (MICROSURFACE_MASK 0). The specialised walk
// reads it from the mask (MICROSURFACE_BITS per interface), the general one from the layer (layer_microsurface), the
// mask then saying only whether any stack it runs has another microsurface.
GONIO_INLINE uint walk_microsurface(uint k) {
    if (MICROSURFACE_MASK == 0u) return 0u;
    if (SPECIALISED) return (MICROSURFACE_MASK >> (MICROSURFACE_BITS * k)) & MICROSURFACE_STATISTICS;
    return layer_microsurface(walk_layer(k)) & MICROSURFACE_STATISTICS;
}

// Whether light walks on interface k's microsurface (`microfacets = "multiple"`; microsurface_walk.glsl). The
// specialised walk reads it from MULTIPLE_MASK (a bit per interface), the general one from the layer, the mask then
// saying only whether any stack it runs has such an interface (where none has, the walk carries none of its code).
GONIO_INLINE bool walk_multiple(uint k) {
    if (MULTIPLE_MASK == 0u) return false;
    if (SPECIALISED) return ((MULTIPLE_MASK >> k) & 1u) != 0u;
    return microsurface_multiple(layer_microsurface(walk_layer(k)));
}

// False where the specialisation says interface k is rough (alpha > 0): the smooth-only code then folds away
// (lavapipe runs both sides of a branch under a mask).
GONIO_INLINE bool walk_may_be_smooth(uint k) { return !(SPECIALISED && ((ROUGH_MASK >> k) & 1u) != 0u); }

// Whether any medium of the stack may scatter (where not, the free-flight code folds away). The general walk reads
// which media scatter from the stack, but SCATTER_MASK != 0 still says whether any of the stacks it runs may: a walk
// built for stacks that do not scatter carries no free-flight code (lavapipe runs both sides of a branch).
GONIO_INLINE bool walk_scatters_any() { return SCATTER_MASK != 0u; }

GONIO_INLINE bool walk_scatters(uint m) {
    if (SPECIALISED) return ((SCATTER_MASK >> m) & 1u) != 0u;
    return layer_medium_scatters(walk_layer(m));
}

// Whether any medium of the stack may be a microflake medium (where none is, the SGGX code folds away); which one is,
// and its S, the walk reads from the layer (layer_medium_phase), general and specialised alike.
GONIO_INLINE bool walk_microflakes_any() { return MICROFLAKE_MASK != 0u; }

// Whether any medium of the stack may absorb without scattering (where not, the Beer-Lambert code folds away).
GONIO_INLINE bool walk_absorbs_any() { return !SPECIALISED || ABSORB_MASK != 0u; }

// Whether medium m is crossed by Beer-Lambert: optical depth above 0, nothing scatters (else the free flight
// attenuates).
GONIO_INLINE bool walk_absorbs(uint m) {
    if (SPECIALISED) return ((ABSORB_MASK >> m) & 1u) != 0u;
    LayerGpu L = walk_layer(m);
    vec3 t = layer_optical_depth(L);
    return (t.x > 0.0f || t.y > 0.0f || t.z > 0.0f) && !layer_medium_scatters(L);
}

// The state of a path between events.
struct Walk {
    vec3 d;           // propagation direction
    vec3 w;           // throughput
    uint k;           // the interface the path is about to hit
    uint reversals;   // direction reversals beneath the top surface
    bool alive;
    bool in_medium;   // inside a scattering medium, between interfaces (p.k is the one ahead along d)
    float z;          // in_medium: depth in the medium in units of its thickness, 0 at its top, 1 at its bottom
};

// Event filters: which interfaces one call of walk_event handles (constant at every call site, so the
// branches for the other kinds fold away after inlining).
const uint EVENTS_ANY = 0u;
const uint EVENTS_DIELECTRIC = 1u;   // the dielectric interfaces above an opaque base
const uint EVENTS_BASE = 2u;         // the opaque base

// The scattering of one event at interface ki (of kind `kind`; walk_event's which, branch and series_base), arriving
// along wi in the interface's local frame (down: from above): its sampler (interface.glsl), Heitz's walk where light
// walks on the microsurface (microsurface_walk.glsl; its own stream from the path's rng), and with `branch` both
// branches of a dielectric, the reflected one written to `reflected` in the global frame (where act).
GONIO_INLINE Scatter walk_sample_interface(uint ki, uint kind, uint which, bool branch, bool series_base, vec3 wi,
                                           float eta, float inv_eta, LayerGpu L, vec4 u, Rng rng, bool down, bool act,
                                           INOUT(vec4) reflected) {
    vec3 cond_eta = layer_conductor_eta(L), cond_k = layer_conductor_k(L), albedo = layer_albedo(L);
    uint micro = walk_microsurface(ki);   // 0 (folded away) on every stack of GGX with height-correlated Smith
    float alpha = walk_alpha(ki);
    Scatter s;
#if GONIO_WALK_MULTIPLE
    if (MULTIPLE_MASK != 0u && kind != KIND_LAMBERTIAN && walk_multiple(ki)) {
        s = sample_microsurface_walk(wi, alpha, micro, kind == KIND_DIELECTRIC, eta, inv_eta, cond_eta, cond_k, u,
                                     microsurface_stream(rng), MICROSURFACE_MAX_MEETINGS);
    } else
#endif
    if (SPECIALISED || which != EVENTS_ANY) {   // the kind is a compile-time constant: one sampler
        if (kind == KIND_DIELECTRIC && branch) {   // (never with a walk on the microsurface: choose_booking)
            vec4 rb;
            s = sample_dielectric_branches(wi, alpha, micro, eta, inv_eta, walk_may_be_smooth(ki), vec2(u.x, u.y), rb);
            vec3 wr = down ? vec3(rb.x, rb.y, rb.z) : vec3(rb.x, rb.y, -rb.z);   // to the global frame
            reflected = act ? vec4(wr.x, wr.y, wr.z, rb.w) : reflected;
        } else if (kind == KIND_DIELECTRIC)
            s = sample_dielectric_inv(wi, alpha, micro, eta, inv_eta, walk_may_be_smooth(ki), u);
        else if (kind == KIND_CONDUCTOR) s = sample_conductor(wi, alpha, micro, cond_eta, cond_k, u);
        else if (series_base) s = sample_lambertian_series(albedo, walk_series().emit, u);
        else s = sample_lambertian(albedo, u);
    } else {                                    // the general walk: the kind is a per-lane value
        Scatter sd = sample_dielectric_inv(wi, alpha, micro, eta, inv_eta, true, u);
        Scatter sc = sample_conductor(wi, alpha, micro, cond_eta, cond_k, u);
        Scatter sl = sample_lambertian(albedo, u);
        s.wo = kind == KIND_DIELECTRIC ? sd.wo : (kind == KIND_CONDUCTOR ? sc.wo : sl.wo);
        s.weight = kind == KIND_DIELECTRIC ? sd.weight : (kind == KIND_CONDUCTOR ? sc.weight : sl.weight);
        s.absorbed = kind == KIND_DIELECTRIC ? sd.absorbed : (kind == KIND_CONDUCTOR ? sc.absorbed : sl.absorbed);
        s.valid = kind == KIND_DIELECTRIC ? sd.valid : (kind == KIND_CONDUCTOR ? sc.valid : sl.valid);
    }
    return s;
}

// One scattering event at interface p.k, then the crossing of the medium the path enters, then Russian
// roulette. Does nothing if the path is dead, has had max_events events, or its interface is not of the kinds
// `which` names. Written without branches on per-lane values (selects only, every state variable assigned
// once): lavapipe runs both sides of every branch under a mask anyway, and a variable assigned in a branch
// costs a masked read-modify-write of a stack slot per assignment. Only the lost energy is accumulated;
// walk_finish() books the absorbed energy as the rest, 1 - lost - w (every change of w is either).
//
// branch (a constant at the call site; trace_book.glsl's first event): a dielectric event with both branches, the
// path refracting with weight (1 - F) G2 / G1 and the reflected branch returned in `reflected` (its direction in the
// global frame, its weight F G2 / G1, 0 where it is invalid) for the caller to book.
GONIO_INLINE void walk_event(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint n, uint which, uint max_events,
                             bool branch, INOUT(vec4) reflected) {
    bool at_base = p.k + 1u == n;
    bool act = p.alive && r.events < max_events && !(walk_scatters_any() && p.in_medium);
    if (which == EVENTS_DIELECTRIC) act = act && !at_base;
    if (which == EVENTS_BASE) act = act && at_base;
    // an opaque base is met from above only
    bool down = (which == EVENTS_BASE && BASE_KIND != KIND_DIELECTRIC) ? true : p.d.z < 0.0f;
    // Lambertian series: the trip's last event (the coat from below), and the base event (SERIES is false on
    // every stack but a dielectric over a Lambertian base, so these fold away elsewhere)
    bool series_exit = SERIES && which == EVENTS_DIELECTRIC && !down;
    bool series_base = SERIES && which == EVENTS_BASE;
    // Local frame of the event: +z towards the side the path arrives from (mirror z when from below).
    vec3 wi = down ? -p.d : vec3(-p.d.x, -p.d.y, p.d.z);
    vec4 u = rng_peek4(rng);
    uint kind = which == EVENTS_DIELECTRIC ? KIND_DIELECTRIC : (which == EVENTS_BASE ? BASE_KIND : walk_kind(p.k));
    // Where the filter pins the interface down, index it with a constant (a uniform load with a per-lane
    // index runs lane by lane on lavapipe).
    uint ki = which == EVENTS_BASE ? LAYER_COUNT - 1u : (which == EVENTS_DIELECTRIC && LAYER_COUNT == 2u ? 0u : p.k);
    LayerGpu L = walk_layer(ki);
    // layer_inv_eta is stored beside layer_eta (stack_gpu.cpp): divisions are the scarce resource of a CPU vector unit
    float eta = down ? layer_eta(L) : layer_inv_eta(L), inv_eta = down ? layer_inv_eta(L) : layer_eta(L);
    vec3 albedo = layer_albedo(L);
    Scatter s = walk_sample_interface(ki, kind, which, branch, series_base, wi, eta, inv_eta, L, u, rng, down, act,
                                      reflected);
    bool valid = s.valid;
    // lost: microfacet loss; with an invalid direction, all that is not absorbed
    vec3 lost = p.w * (vec3(1.0f) - s.absorbed - (valid ? s.weight : vec3(0.0f)));
    // series: the expected loss of all trips is booked at the base, none where the trip ends
    if (SERIES) {
        vec4 sl = walk_series().lost;
        vec3 ls = vec3(sl.x, sl.y, sl.z);
        lost = series_base ? p.w * albedo * vec3(ls.x, ls.y, ls.z) : (series_exit ? vec3(0.0f) : lost);
    }
    vec3 w = p.w * s.weight;
    vec3 d = down ? s.wo : vec3(s.wo.x, s.wo.y, -s.wo.z);
    bool now_down = d.z < 0.0f;
    bool reversal = valid && now_down != down && !(p.k == 0u && down);
    bool leaves_bottom = valid && now_down && at_base;    // through the bottom of a transmissive stack
    bool leaves_top = valid && !now_down && p.k == 0u;    // through the top
    bool moves = valid && !leaves_bottom && !leaves_top && !series_exit;
    uint medium = now_down ? p.k : max(p.k, 1u) - 1u;   // (for a path leaving through the top: unused)
    // Beer-Lambert through the medium: tau / |cos| per crossing.
    vec3 wm = w;
    if (walk_absorbs_any()) {
        vec3 t = layer_optical_depth((SPECIALISED && LAYER_COUNT == 2u) ? walk_layer(0u) : walk_layer(medium));
        vec3 a = exp(-t * (1.0f / max(abs(d.z), 1e-30f)));
        wm = walk_absorbs(medium) ? w * a : w;
    }
    // Russian roulette (unbiased): survive with q = max(w) / RR_THRESHOLD, divide by q.
    float wmax = max(wm.x, max(wm.y, wm.z));
    bool rr = wmax < RR_THRESHOLD;
    float q = wmax * (1.0f / RR_THRESHOLD);
    bool killed = moves && rr && u.w >= q;
    vec3 wr = rr ? wm * (RR_THRESHOLD / wmax) : wm;      // 1 / q without a second division
    bool alive = moves && !killed;
    bool ends = !valid || killed || (series_exit && !leaves_top);   // series: reflected back at the trip's end
    uint outcome = ends ? OUTCOME_ENDED
                 : (leaves_bottom ? OUTCOME_TRANSMITTED : (leaves_top ? OUTCOME_REFLECTED : r.outcome));
    vec4 sg = walk_series().gain;
    vec3 gain = SERIES ? vec3(sg.x, sg.y, sg.z) : vec3(1.0f);
    vec3 w_next = alive ? wr : (ends ? vec3(0.0f) : (series_exit ? w * gain : w));
    // every state variable assigned once
    rng.key.w += act ? 1u : 0u;
    r.events += act ? 1u : 0u;
    r.lost = act ? r.lost + lost : r.lost;
    r.outcome = act ? outcome : r.outcome;
    p.reversals += act && reversal ? 1u : 0u;
    p.k = act && moves ? (now_down ? p.k + 1u : p.k - 1u) : p.k;
    p.d = act && valid ? d : p.d;
    p.w = act ? w_next : p.w;
    p.alive = act ? alive : p.alive;
    // a path that moves into a scattering medium flies there first (walk_medium_event), from its top or bottom
    if (walk_scatters_any()) {
        bool enters = act && alive && walk_scatters(medium);
        p.in_medium = enters ? true : p.in_medium;
        p.z = enters ? (now_down ? 0.0f : 1.0f) : p.z;
    }
}

// One event of a path inside a scattering medium (p.in_medium): a free flight from depth p.z along p.d
// (sample_free_flight, medium.glsl, with the channels chosen in proportion to the throughput). It either collides,
// a scattering event: the single-scattering albedo, a new direction from the medium's phase function (Henyey-Greenstein,
// or a specular microflake's, whose projected area also scales the extinction along d), Russian roulette; or it reaches
// the interface ahead, where the path leaves the medium (the next interface event is at p.k). Does nothing for a
// path that is not in a medium, is dead, or has had max_events events; a flight that reaches an interface is not an
// event (the interface event that follows in the same walk_step is).
GONIO_INLINE void walk_medium_event(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint max_events) {
    bool act = p.alive && p.in_medium && r.events < max_events;
    bool down = p.d.z < 0.0f;
    uint m = down ? max(p.k, 1u) - 1u : p.k;   // the medium between interfaces m and m + 1
    // where the specialisation says only one medium scatters, a path in a medium is in that one: its layer is read
    // with a constant index (with a per-lane index a uniform load runs lane by lane on lavapipe)
    bool one_medium = SPECIALISED && SCATTER_MASK != 0u && (SCATTER_MASK & (SCATTER_MASK - 1u)) == 0u;
    uint mi = (SPECIALISED && LAYER_COUNT == 2u) ? 0u : (one_medium ? uint(findLSB(SCATTER_MASK)) : m);
    LayerGpu L = walk_layer(mi);
    vec3 tau = layer_optical_depth(L), omega = layer_scattering_albedo(L);
    vec4 u = rng_peek4(rng);   // channel (and what it leaves, for Russian roulette), distance, the phase function's two
    float s_max = (down ? 1.0f - p.z : p.z) / max(abs(p.d.z), 1e-30f);
    float wsum = p.w.x + p.w.y + p.w.z;
    vec3 prob = wsum > 0.0f ? p.w * (1.0f / wsum) : vec3(1.0f / 3.0f);
    vec3 S = vec3(1.0f);   // a microflake medium's S (diagonal), where there is one
    bool microflakes = false;
    if (walk_microflakes_any()) {
        microflakes = layer_medium_phase(L) != MEDIUM_PHASE_HG;
        S = sggx_diagonal(layer_medium_phase(L), layer_microflake_alpha(L));
        tau = microflakes ? tau * sggx_projected_area(S, p.d) : tau;
    }
    FreeFlight f = sample_free_flight(tau, s_max, prob, u.x, u.y);
    bool hit = f.scattered;
    vec3 w = p.w * f.weight * (hit ? omega : vec3(1.0f));
    vec3 d = hit ? sample_henyey_greenstein(p.d, layer_phase_g(L), u.z, u.w) : p.d;
    if (walk_microflakes_any()) d = hit && microflakes ? sample_sggx_specular(S, p.d, u.z, u.w) : d;
    float z = hit ? clamp(p.z - p.d.z * f.s, 0.0f, 1.0f) : p.z;   // z grows downwards, along -d.z
    bool now_down = d.z < 0.0f;
    // Russian roulette after a collision, as at an interface (unbiased: survive with q = max(w) / RR_THRESHOLD)
    float wmax = max(w.x, max(w.y, w.z));
    bool rr = hit && wmax < RR_THRESHOLD;
    bool killed = rr && f.u_rest >= wmax * (1.0f / RR_THRESHOLD);
    vec3 wr = rr && !killed ? w * (RR_THRESHOLD / wmax) : w;
    rng.key.w += act ? 1u : 0u;
    r.events += act && hit ? 1u : 0u;
    r.outcome = act && killed ? OUTCOME_ENDED : r.outcome;
    p.reversals += act && hit && now_down != down ? 1u : 0u;   // scattered back: a reversal beneath the top
    p.k = act ? (now_down ? m + 1u : m) : p.k;
    p.d = act ? d : p.d;
    p.z = act ? z : p.z;
    p.w = act ? (killed ? vec3(0.0f) : wr) : p.w;
    p.alive = act ? !killed : p.alive;
    p.in_medium = act ? hit && !killed : p.in_medium;
}

// A path in flight (walk_begin, walk_step, walk_finish); trace_path runs one to the end.
// travel: the incident light's direction of travel (bins.glsl incident_travel)
GONIO_INLINE void walk_begin(OUT(Walk) p, OUT(PathResult) r, vec3 travel) {
    r.absorbed = vec3(0.0f);
    r.lost = vec3(0.0f);
    r.outcome = OUTCOME_TRUNCATED;
    r.events = 0u;
    r.weight = vec3(0.0f);
    r.dir = vec3(0.0f);
    r.order = 0u;
    p.d = travel;
    p.w = vec3(1.0f);
    p.k = 0u;
    p.reversals = 0u;
    p.alive = true;
    p.in_medium = false;
    p.z = 0.0f;
}

// One step of the walk. Above an opaque base a step runs the dielectric events and then the base event:
// lanes of a SIMD group that are at different interfaces do not each pay for both kinds on every step (a path
// at the base always leaves it upwards, so on a two-layer stack the two phases alternate exactly).
// In a stack whose media scatter, a step begins with the flight of the paths in a medium (a path that reaches an
// interface meets it in the same step: every step of a live path has an event, so max_events steps suffice).
// Returns false once the path has ended (left, absorbed, lost, or reached max_events).
GONIO_INLINE bool walk_step(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint max_events) {
    uint n = walk_layer_count();
    vec4 unused = vec4(0.0f);
    if (walk_scatters_any()) walk_medium_event(p, r, rng, max_events);
    if (SPECIALISED && BASE_KIND != KIND_DIELECTRIC && LAYER_COUNT > 1u) {
        walk_event(p, r, rng, n, EVENTS_DIELECTRIC, max_events, false, unused);
        walk_event(p, r, rng, n, EVENTS_BASE, max_events, false, unused);
    } else {
        walk_event(p, r, rng, n, EVENTS_ANY, max_events, false, unused);
    }
    if (walk_scatters_any()) walk_medium_event(p, r, rng, max_events);
    return p.alive && r.events < max_events;
}

GONIO_INLINE void walk_finish(INOUT(Walk) p, INOUT(PathResult) r) {
    r.absorbed = vec3(1.0f) - r.lost - p.w;   // absorbed = everything neither lost nor still carried
    r.weight = p.w;
    r.dir = p.d;
    r.order = min(p.reversals, 2u);
}

// Whether everything a finished path books is a finite number (its weight, absorbed and lost energy and its exit
// direction): one that is not (a bug in a sampler or a formula) is booked in the invalid class alone, never as
// absorbed or leaving (tally.glsl). Comparisons that NaN and Inf fail, in GLSL and in C++ alike.
GONIO_INLINE bool path_is_finite(PathResult r) {
    float s = r.weight.x + r.weight.y + r.weight.z + r.absorbed.x + r.absorbed.y + r.absorbed.z + r.lost.x + r.lost.y +
              r.lost.z + r.dir.x + r.dir.y + r.dir.z;
    return s > -1e30f && s < 1e30f;
}

GONIO_INLINE PathResult trace_path(vec3 travel, INOUT(Rng) rng, uint max_events) {
    Walk p;
    PathResult r;
    walk_begin(p, r, travel);
    if (SERIES) {   // straight-line: the coat from above, the base, the coat from below (max_events >= 3)
        uint n = walk_layer_count();
        vec4 unused = vec4(0.0f);
        walk_event(p, r, rng, n, EVENTS_DIELECTRIC, max_events, false, unused);
        walk_event(p, r, rng, n, EVENTS_BASE, max_events, false, unused);
        walk_event(p, r, rng, n, EVENTS_DIELECTRIC, max_events, false, unused);
    } else {
        for (uint it = 0u; it < max_events; ++it)
            if (!walk_step(p, r, rng, max_events)) break;
    }
    walk_finish(p, r);
    return r;
}
#endif
