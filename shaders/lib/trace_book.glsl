// trace_book.glsl: one path traced (walk.glsl) and booked (tally.glsl), with two estimators that book some of a path's
// light where it could leave rather than where it does: the entry's both branches and the exit estimate at the base
// (docs/PHYSICS.md, "Booking estimators"). For simulate_path.glsl and the CPU twin. Needs walk.glsl, tally.glsl and
// two specialisation constants, ENTRY_BRANCH and EXIT_ESTIMATE (bool), which the host sets where they apply
// (stack_gpu.cpp, choose_booking).
//
// The entry's both branches (ENTRY_BRANCH): at the path's first event, a dielectric top met from above, the walk does
// not choose between reflection and refraction: the reflected branch is booked, weight F G2 / G1 (m from the
// visible normals), and the path refracts with weight (1 - F) G2 / G1 of the same m. The expectation is the analog
// walk's; every path, not a fraction F of them, books a sample of the coat's reflection lobe, whose bins (the peak of
// a glossy coat's slice) otherwise wait for the rare reflected paths.
//
// The exit estimate (EXIT_ESTIMATE; two interfaces, no medium that scatters, over a conductor base or a slab's): the
// light that leaves right after the path's first base event (over a conductor: base -> coat -> out, Beer-Lambert on
// the way up; a slab: out through the base) is estimated twice: by the path's own continuation and by a fresh one (a
// base direction, the coat's attenuation, the coat's refracted branch; a slab: the base's refracted branch of a fresh
// microfacet), each booked with weight 1/2. Everything else the path does (reflections inside the coat, later
// base events, the exits after them) is booked as before. Both estimates have the expectation of the direct exit,
// so their mean is unbiased; they share only the arriving direction.
//
// A path's bookings that fall in one bin are summed before they are booked (tally_exit): a bin's sum of squares is
// then the paths' squares, and its standard error stays honest.
//
// Energy book: the path's lost energy is its own (its microfacet losses, the entry's two branches' included; the
// fresh estimate books nothing lost); absorbed is the rest, 1 - lost - booked - truncated, so the per-path balance
// holds exactly and absorbed is unbiased (as under Russian roulette, one path may book a negative absorption).
#ifndef GONIO_TRACE_BOOK_GLSL
#define GONIO_TRACE_BOOK_GLSL

GONIO_INLINE bool exit_estimate_applies() {
    return EXIT_ESTIMATE && SPECIALISED && LAYER_COUNT == 2u && SCATTER_MASK == 0u && !SERIES &&
           (BASE_KIND == KIND_CONDUCTOR || BASE_KIND == KIND_DIELECTRIC);
}

// The random stream of what a path books beside its own exit (the exit estimate, the entry's reflected branch, and
// their dithering): the path's key with the top bit of its high word set (a path index is below 2^63, so no path's
// own stream has it), counted from 0.
GONIO_INLINE Rng side_stream(Rng path) {
    Rng e;
    e.key = uvec4(path.key.x, path.key.y | 0x80000000u, path.key.z, 0u);
    return e;
}

// Whether a booked weight and its direction are finite numbers (a NaN or Inf fails every comparison).
GONIO_INLINE bool booking_is_finite(vec3 x, vec3 dir) {
    float s = x.x + x.y + x.z + dir.x + dir.y + dir.z;
    return s > -1e30f && s < 1e30f;
}

// A booking held until the path ends (its bin, its weight; weight 0: none).
struct Booking {
    uint bin;
    vec3 w;
};

// The fresh exit estimate of a path that arrives at the base along d with weight w (before the base event), with
// weight 1/2, in class cls; its bin (or weight 0 where it does not leave). A non-finite estimate is returned as such.
GONIO_INLINE Booking exit_estimate(vec3 d, vec3 w, uint cls, INOUT(Rng) e, Tally t) {
    LayerGpu coat = walk_layer(0u), base = walk_layer(1u);
    vec3 wi = -d;   // the base is met from above: its local frame is the global one
    vec4 u = rng_next4(e);
    Scatter b = sample_conductor(wi, walk_alpha(1u), layer_conductor_eta(base), layer_conductor_k(base), u);
    vec3 up = b.wo;
    vec3 a = walk_absorbs(0u) ? exp(-layer_optical_depth(coat) * (1.0f / max(up.z, 1e-30f))) : vec3(1.0f);
    // the coat from below: local frame mirrored in z, eta = n_air / n_coat
    vec3 wc = vec3(-up.x, -up.y, up.z);
    vec4 unused;
    Scatter c = sample_dielectric_branches(wc, walk_alpha(0u), layer_inv_eta(coat), layer_eta(coat),
                                           walk_may_be_smooth(0u), vec2(u.z, u.w), unused);
    vec3 out_dir = vec3(c.wo.x, c.wo.y, -c.wo.z);
    bool books = b.valid && c.valid;
    vec3 x = w * b.weight * a * c.weight * 0.5f;
    bool ok = booking_is_finite(x, out_dir);
    Booking k;
    k.w = books ? (ok ? x : vec3(uintBitsToFloat(0x7fc00000u))) : vec3(0.0f);
    k.bin = books && ok ? tally_bin(t, out_dir, 0u, cls) : 0u;
    return k;
}

// The fresh exit estimate of a path that arrives along d with weight w at the base of a slab (a dielectric base met
// from above): the base's refracted branch of a fresh microfacet, weight 1/2, class cls, on the transmitted side.
GONIO_INLINE Booking exit_estimate_through_base(vec3 d, vec3 w, uint cls, INOUT(Rng) e, Tally t) {
    LayerGpu base = walk_layer(1u);
    vec3 wi = -d;   // met from above: its local frame is the global one
    vec4 u = rng_next4(e);
    vec4 unused;
    Scatter c = sample_dielectric_branches(wi, walk_alpha(1u), layer_eta(base), layer_inv_eta(base),
                                           walk_may_be_smooth(1u), vec2(u.x, u.y), unused);
    vec3 x = w * c.weight * 0.5f;
    bool ok = booking_is_finite(x, c.wo);
    Booking k;
    k.w = c.valid ? (ok ? x : vec3(uintBitsToFloat(0x7fc00000u))) : vec3(0.0f);
    k.bin = c.valid && ok ? tally_bin(t, c.wo, 1u, cls) : 0u;
    return k;
}

// The walk's first step (walk_step's events in its order), the first event with both branches where ENTRY_BRANCH
// says so (its reflected branch in `reflected`: direction, weight), and the exit estimate where it applies. Returns
// the reversals the path's own direct exit after the estimated base event has (it leaves as `direct_outcome`), or
// 0xffffffff where there was none. On a slab the base event is the next step's: the estimate is drawn before it.
GONIO_INLINE uint trace_first_step(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint max_events,
                                   INOUT(vec4) reflected, INOUT(Rng) e, INOUT(Booking) estimate, Tally t,
                                   OUT(uint) direct_outcome) {
    uint n = walk_layer_count();
    bool branch = ENTRY_BRANCH && SPECIALISED && !SERIES;
    vec4 unused = vec4(0.0f);
    if (SPECIALISED && BASE_KIND != KIND_DIELECTRIC && LAYER_COUNT > 1u) {   // two-phase steps (walk_step)
        walk_event(p, r, rng, n, EVENTS_DIELECTRIC, max_events, branch, reflected);
        // the direct exit after the base event within the event cap
        bool estimated = exit_estimate_applies() && p.alive && p.k == 1u && r.events + 2u <= max_events;
        if (estimated) estimate = exit_estimate(p.d, p.w, ORDERS ? min(p.reversals + 1u, 2u) : 0u, e, t);
        walk_event(p, r, rng, n, EVENTS_BASE, max_events, false, unused);
        if (walk_scatters_any()) walk_medium_event(p, r, rng, max_events);
        direct_outcome = OUTCOME_REFLECTED;
        return estimated ? p.reversals : 0xffffffffu;
    }
    // a path starts above the stack, in no medium: walk_step's first flight does nothing
    walk_event(p, r, rng, n, EVENTS_ANY, max_events, branch, reflected);
    if (walk_scatters_any()) walk_medium_event(p, r, rng, max_events);
    // a slab: the exit through its base, the next event (within the event cap)
    bool estimated = exit_estimate_applies() && BASE_KIND == KIND_DIELECTRIC && p.alive && p.k == 1u &&
                     r.events + 1u <= max_events;
    if (estimated) estimate = exit_estimate_through_base(p.d, p.w, ORDERS ? min(p.reversals, 2u) : 0u, e, t);
    direct_outcome = OUTCOME_TRANSMITTED;
    return estimated ? p.reversals : 0xffffffffu;
}

// The path's own exit and the bookings it holds (the entry's reflected branch, the exit estimate), those in one bin
// summed; the held ones booked from the side stream, the path's own by tally_path_at. booked: their weight (NaN
// where one is not finite: the path is then booked as invalid).
GONIO_INLINE void book_held(INOUT(Tally) t, INOUT(PathResult) r, Booking held0, Booking held1, INOUT(Rng) rng,
                            INOUT(Rng) e, uint staging_base) {
    bool finite = booking_is_finite(held0.w, vec3(0.0f)) && booking_is_finite(held1.w, vec3(0.0f));
    bool own = finite && path_leaves(r) && path_is_finite(r);
    uint bin = own ? path_bin(t, r) : 0xffffffffu;
    bool h0 = finite && (held0.w.x > 0.0f || held0.w.y > 0.0f || held0.w.z > 0.0f);
    bool h1 = finite && (held1.w.x > 0.0f || held1.w.y > 0.0f || held1.w.z > 0.0f);
    vec3 booked = finite ? held0.w + held1.w : vec3(uintBitsToFloat(0x7fc00000u));
    if (h1 && h0 && held1.bin == held0.bin) {
        held0.w += held1.w;
        h1 = false;
    }
    if (h0 && own && held0.bin == bin) {
        r.weight += held0.w;
        h0 = false;
    }
    if (h1 && own && held1.bin == bin) {
        r.weight += held1.w;
        h1 = false;
    }
    if (h0) tally_exit(t, held0.bin, held0.w, e, staging_base);
    if (h1) tally_exit(t, held1.bin, held1.w, e, staging_base);
    r.absorbed -= booked;
    tally_path_at(t, r, bin, rng, staging_base);
}

// One path traced and booked: trace_path and tally_path, with the entry's both branches and the exit estimate where
// they apply. poison (for the tests of the invalid class only): the path's weight is made NaN.
GONIO_INLINE void trace_and_book(float sin_ti, float cos_ti, INOUT(Rng) rng, uint max_events, INOUT(Tally) t,
                                 uint staging_base, bool poison) {
    if (!(ENTRY_BRANCH && SPECIALISED && !SERIES) && !exit_estimate_applies()) {
        PathResult r = trace_path(sin_ti, cos_ti, rng, max_events);
        if (poison) r.weight.x = uintBitsToFloat(0x7fc00000u);
        tally_path(t, r, rng, staging_base);
        return;
    }
    Walk p;
    PathResult r;
    walk_begin(p, r, sin_ti, cos_ti);
    Rng e = side_stream(rng);
    vec4 reflected = vec4(0.0f);
    Booking estimate;
    estimate.bin = 0u;
    estimate.w = vec3(0.0f);
    uint direct_outcome;
    uint reversals_estimated = trace_first_step(p, r, rng, max_events, reflected, e, estimate, t, direct_outcome);
    Booking entry;   // the entry's reflected branch: a direct reflection, class 0
    vec3 rdir = vec3(reflected.x, reflected.y, reflected.z);
    bool ok = booking_is_finite(vec3(reflected.w), rdir);
    entry.w = ok ? vec3(reflected.w) : (reflected.w != 0.0f ? vec3(uintBitsToFloat(0x7fc00000u)) : vec3(0.0f));
    entry.bin = ok && reflected.w > 0.0f ? tally_bin(t, rdir, 0u, 0u) : 0u;
    for (uint it = 1u; it < max_events; ++it)
        if (!(p.alive && r.events < max_events) || !walk_step(p, r, rng, max_events)) break;
    walk_finish(p, r);
    // the path's own exit right after the estimated base event is the other half of the estimate
    bool direct = r.outcome == direct_outcome && p.reversals == reversals_estimated;
    r.absorbed += direct ? 0.5f * r.weight : vec3(0.0f);
    r.weight = direct ? 0.5f * r.weight : r.weight;
    if (poison) r.weight.x = uintBitsToFloat(0x7fc00000u);
    book_held(t, r, entry, estimate, rng, e, staging_base);
}
#endif
