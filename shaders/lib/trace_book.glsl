// trace_book.glsl: one path traced (walk.glsl) and booked (tally.glsl), with two estimators that book some of a path's
// light where it could leave rather than where it does: the entry's both branches and the exit estimate at the base
// (docs/PHYSICS.md, "Booking estimators"). For simulate_path.glsl and the CPU twin. Needs walk.glsl, tally.glsl and
// two specialisation constants, ENTRY_BRANCH (bool) and EXIT_ESTIMATES (uint, 0 to kernel_interface.glsl's
// MAX_EXIT_ESTIMATES), which the host sets where they apply (stack_gpu.cpp, choose_booking), and FAULT_FOR_TESTS
// (FAULT_NONE but in the tests' negative controls).
//
// The entry's both branches (ENTRY_BRANCH): at the path's first event, a dielectric top met from above, the walk does
// not choose between reflection and refraction: the reflected branch is booked, weight F G2 / G1 (m from the
// visible normals), and the path refracts with weight (1 - F) G2 / G1 of the same m. The expectation is the analog
// walk's; every path, not a fraction F of them, books a sample of the coat's reflection lobe, whose bins (the peak of
// a glossy coat's slice) otherwise wait for the rare reflected paths.
//
// The exit estimates (EXIT_ESTIMATES = K > 0; two interfaces, no medium that scatters, over a conductor base or a
// slab's): the light that leaves right after the path's first base event (over a conductor: base -> coat -> out,
// Beer-Lambert on the way up; a slab: out through the base) is estimated K + 1 times: by the path's own continuation
// and by K fresh ones (a base direction, the coat's attenuation, the coat's refracted branch; a slab: the base's
// refracted branch of a fresh microfacet), each booked with weight 1 / (K + 1). The fresh ones are stratified: the
// j-th draws its microfacet's azimuth from the j-th of K equal parts of [0, 1) (each alone is not uniform, their sum
// is an unbiased estimate). Everything else the path does (reflections inside the coat, later base events, the exits
// after them) is booked as before. Every estimate's expectation is the direct exit, so the mean is unbiased; the
// fresh ones share only the arriving direction with the path.
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
    return EXIT_ESTIMATES > 0u && SPECIALISED && LAYER_COUNT == 2u && SCATTER_MASK == 0u && !SERIES &&
           (BASE_KIND == KIND_CONDUCTOR || BASE_KIND == KIND_DIELECTRIC);
}

// The weight of each of the direct exit's K + 1 estimates.
GONIO_INLINE float exit_estimate_share() { return 1.0f / float(EXIT_ESTIMATES + 1u); }

// The j-th of K strata of [0, 1) for a uniform u (below 1: (K - 1 + u) / K can round up to 1 in float).
GONIO_INLINE float exit_stratum(float u, uint j) {
    return min((float(j) + u) * (1.0f / float(max(EXIT_ESTIMATES, 1u))), 0.99999994f);
}

// The random stream of what a path books beside its own exit (the exit estimates, the entry's reflected branch, and
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

// A booking held until the path ends (its bin, NO_BIN for none; its weight).
const uint NO_BIN = 0xffffffffu;
struct Booking {
    uint bin;
    vec3 w;
};

GONIO_INLINE Booking no_booking() {
    Booking k;
    k.bin = NO_BIN;
    k.w = vec3(0.0f);
    return k;
}

// A booking of weight x in direction dir (side, class) where `books`; NaN where x or dir is not finite.
GONIO_INLINE Booking held_booking(bool books, vec3 x, vec3 dir, uint side, uint cls, Tally t) {
    bool ok = booking_is_finite(x, dir);
    Booking k;
    k.w = books ? (ok ? x : vec3(uintBitsToFloat(0x7fc00000u))) : vec3(0.0f);
    k.bin = books && ok ? tally_bin(t, dir, side, cls) : NO_BIN;
    return k;
}

// The j-th fresh exit estimate of a path that arrives at the base along d with weight w (before the base event), with
// weight exit_estimate_share(), in class cls; its bin (or weight 0 where it does not leave).
GONIO_INLINE Booking exit_estimate(vec3 d, vec3 w, uint cls, uint j, INOUT(Rng) e, Tally t) {
    LayerGpu coat = walk_layer(0u), base = walk_layer(1u);
    vec3 wi = -d;   // the base is met from above: its local frame is the global one
    vec4 u = rng_next4(e);
    u.x = exit_stratum(u.x, j);
    Scatter b = sample_conductor(wi, walk_alpha(1u), walk_microsurface(1u), layer_conductor_eta(base),
                                 layer_conductor_k(base), u);
    vec3 up = b.wo;
    vec3 a = walk_absorbs(0u) ? exp(-layer_optical_depth(coat) * (1.0f / max(up.z, 1e-30f))) : vec3(1.0f);
    // the coat from below: local frame mirrored in z, eta = n_air / n_coat
    vec3 wc = vec3(-up.x, -up.y, up.z);
    vec4 unused;
    Scatter c = sample_dielectric_branches(wc, walk_alpha(0u), walk_microsurface(0u), layer_inv_eta(coat),
                                           layer_eta(coat), walk_may_be_smooth(0u), vec2(u.z, u.w), unused);
    vec3 out_dir = vec3(c.wo.x, c.wo.y, -c.wo.z);
    return held_booking(b.valid && c.valid, w * b.weight * a * c.weight * exit_estimate_share(), out_dir, 0u, cls, t);
}

// The j-th fresh exit estimate of a path that arrives along d with weight w at the base of a slab (a dielectric base
// met from above): the base's refracted branch of a fresh microfacet, weight exit_estimate_share(), class cls, on the
// transmitted side.
GONIO_INLINE Booking exit_estimate_through_base(vec3 d, vec3 w, uint cls, uint j, INOUT(Rng) e, Tally t) {
    LayerGpu base = walk_layer(1u);
    vec3 wi = -d;   // met from above: its local frame is the global one
    vec4 u = rng_next4(e);
    vec4 unused;
    Scatter c = sample_dielectric_branches(wi, walk_alpha(1u), walk_microsurface(1u), layer_eta(base),
                                           layer_inv_eta(base), walk_may_be_smooth(1u), vec2(exit_stratum(u.x, j), u.y),
                                           unused);
    return held_booking(c.valid, w * c.weight * exit_estimate_share(), c.wo, 1u, cls, t);
}

// The j-th fresh exit estimate (a constant), from the base (slab) or to the base (conductor), for a path that arrived
// there along d with weight w, class cls.
GONIO_INLINE Booking exit_estimate_number(uint j, vec3 d, vec3 w, uint cls, INOUT(Rng) e, Tally t) {
    return BASE_KIND == KIND_DIELECTRIC ? exit_estimate_through_base(d, w, cls, j, e, t)
                                        : exit_estimate(d, w, cls, j, e, t);
}

// The path's fresh exit estimates (the first EXIT_ESTIMATES of est0 to est5). Separate variables, not an array: on
// lavapipe an array of bookings lives in memory (measured: 3x slower paths).
GONIO_INLINE void exit_estimates(vec3 d, vec3 w, uint cls, INOUT(Rng) e, Tally t, INOUT(Booking) est0,
                                 INOUT(Booking) est1, INOUT(Booking) est2, INOUT(Booking) est3, INOUT(Booking) est4,
                                 INOUT(Booking) est5) {
    est0 = exit_estimate_number(0u, d, w, cls, e, t);
    if (EXIT_ESTIMATES > 1u) est1 = exit_estimate_number(1u, d, w, cls, e, t);
    if (EXIT_ESTIMATES > 2u) est2 = exit_estimate_number(2u, d, w, cls, e, t);
    if (EXIT_ESTIMATES > 3u) est3 = exit_estimate_number(3u, d, w, cls, e, t);
    if (EXIT_ESTIMATES > 4u) est4 = exit_estimate_number(4u, d, w, cls, e, t);
    if (EXIT_ESTIMATES > 5u) est5 = exit_estimate_number(5u, d, w, cls, e, t);
}

// The walk's first step (walk_step's events in its order), the first event with both branches where ENTRY_BRANCH
// says so (its reflected branch in `reflected`: direction, weight), and the exit estimates where they apply. Returns
// the reversals the path's own direct exit after the estimated base event has (it leaves as `direct_outcome`), or
// 0xffffffff where there was none. On a slab the base event is the next step's: the estimates are drawn before it.
GONIO_INLINE uint trace_first_step(INOUT(Walk) p, INOUT(PathResult) r, INOUT(Rng) rng, uint max_events,
                                   INOUT(vec4) reflected, INOUT(vec3) arrival, INOUT(vec3) arrival_w,
                                   INOUT(uint) arrival_cls, OUT(uint) direct_outcome) {
    uint n = walk_layer_count();
    bool branch = ENTRY_BRANCH && SPECIALISED && !SERIES;
    vec4 unused = vec4(0.0f);
    if (SPECIALISED && BASE_KIND != KIND_DIELECTRIC && LAYER_COUNT > 1u) {   // two-phase steps (walk_step)
        walk_event(p, r, rng, n, EVENTS_DIELECTRIC, max_events, branch, reflected);
        // the direct exit after the base event within the event cap
        bool estimated = exit_estimate_applies() && p.alive && p.k == 1u && r.events + 2u <= max_events;
        arrival = estimated ? p.d : arrival;
        arrival_w = estimated ? p.w : arrival_w;
        arrival_cls = ORDERS ? min(p.reversals + 1u, 2u) : 0u;
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
    arrival = estimated ? p.d : arrival;
    arrival_w = estimated ? p.w : arrival_w;
    arrival_cls = ORDERS ? min(p.reversals, 2u) : 0u;
    direct_outcome = OUTCOME_TRANSMITTED;
    return estimated ? p.reversals : 0xffffffffu;
}

GONIO_INLINE bool booking_held(Booking k) { return k.bin != NO_BIN; }
GONIO_INLINE bool same_bin(Booking a, Booking b) { return a.bin == b.bin && a.bin != NO_BIN; }

// A held booking booked (tally_exit, dithered from e) unless it is in the path's own bin (`own`: the path leaves
// into bin `bin`), where it is added to the path's weight.
GONIO_INLINE void book_one_held(INOUT(Tally) t, INOUT(PathResult) r, Booking k, bool own, uint bin, INOUT(Rng) e,
                                uint staging_base) {
    bool held = booking_held(k);
    bool joins = held && own && k.bin == bin && FAULT_FOR_TESTS != FAULT_BOOKINGS_SQUARED_APART;
    r.weight = joins ? r.weight + k.w : r.weight;
    if (held && !joins) tally_exit(t, k.bin, k.w, e, staging_base);
}

// b's weight added to a's where both are held in one bin (b then holds nothing).
GONIO_INLINE void booking_merge(INOUT(Booking) a, INOUT(Booking) b) {
    bool same = same_bin(a, b);
    a.w = same ? a.w + b.w : a.w;
    b.w = same ? vec3(0.0f) : b.w;
    b.bin = same ? NO_BIN : b.bin;
}

// The path's own exit, the entry's reflected branch and the fresh exit estimates (where `estimated`: drawn here, for
// a path that arrived at the base along `arrival` with weight arrival_w, class cls: drawn after the walk, so that
// nothing of them is held through it), those in one bin summed and booked once; the held ones booked from the side
// stream e, the path's own by tally_path_at. A non-finite booking makes the path's absorbed energy NaN (it is then
// booked as invalid).
GONIO_INLINE void book_path_and_estimates(INOUT(Tally) t, INOUT(PathResult) r, Booking entry, bool estimated,
                                          vec3 arrival, vec3 arrival_w, uint cls, INOUT(Rng) rng, INOUT(Rng) e,
                                          uint staging_base) {
    Booking est0 = no_booking(), est1 = no_booking(), est2 = no_booking();
    Booking est3 = no_booking(), est4 = no_booking(), est5 = no_booking();
    if (estimated) exit_estimates(arrival, arrival_w, cls, e, t, est0, est1, est2, est3, est4, est5);
    vec3 booked = entry.w + est0.w + est1.w + est2.w + est3.w + est4.w + est5.w;
    bool finite = booking_is_finite(booked, vec3(0.0f));
    bool own = finite && path_leaves(r) && path_is_finite(r);
    uint bin = own ? path_bin(t, r) : 0xffffffffu;
    if (finite) {   // each booking into the first earlier one in its bin (those never held fold away)
        // rare (two bookings in one bin): merged only where a lane of the SIMD group has one
        bool any_same = same_bin(entry, est0) || same_bin(entry, est1) || same_bin(est0, est1) ||
                        same_bin(entry, est2) || same_bin(est0, est2) || same_bin(est1, est2) ||
                        same_bin(entry, est3) || same_bin(est0, est3) || same_bin(est1, est3) || same_bin(est2, est3) ||
                        same_bin(entry, est4) || same_bin(est0, est4) || same_bin(est1, est4) || same_bin(est2, est4) ||
                        same_bin(est3, est4) || same_bin(entry, est5) || same_bin(est0, est5) || same_bin(est1, est5) ||
                        same_bin(est2, est5) || same_bin(est3, est5) || same_bin(est4, est5);
        if (any_same && FAULT_FOR_TESTS != FAULT_BOOKINGS_SQUARED_APART) {
            booking_merge(entry, est0); booking_merge(entry, est1); booking_merge(est0, est1);
            booking_merge(entry, est2); booking_merge(est0, est2); booking_merge(est1, est2);
            booking_merge(entry, est3); booking_merge(est0, est3); booking_merge(est1, est3); booking_merge(est2, est3);
            booking_merge(entry, est4); booking_merge(est0, est4); booking_merge(est1, est4); booking_merge(est2, est4);
            booking_merge(est3, est4); booking_merge(entry, est5); booking_merge(est0, est5); booking_merge(est1, est5);
            booking_merge(est2, est5); booking_merge(est3, est5); booking_merge(est4, est5);
        }
        book_one_held(t, r, entry, own, bin, e, staging_base);
        book_one_held(t, r, est0, own, bin, e, staging_base);
        if (EXIT_ESTIMATES > 1u) book_one_held(t, r, est1, own, bin, e, staging_base);
        if (EXIT_ESTIMATES > 2u) book_one_held(t, r, est2, own, bin, e, staging_base);
        if (EXIT_ESTIMATES > 3u) book_one_held(t, r, est3, own, bin, e, staging_base);
        if (EXIT_ESTIMATES > 4u) book_one_held(t, r, est4, own, bin, e, staging_base);
        if (EXIT_ESTIMATES > 5u) book_one_held(t, r, est5, own, bin, e, staging_base);
    }
    r.absorbed -= finite ? booked : vec3(uintBitsToFloat(0x7fc00000u));
    tally_path_at(t, r, bin, rng, staging_base);
}

// One path traced and booked: trace_path and tally_path, with the entry's both branches and the exit estimates where
// they apply. poison (for the tests of the invalid class only): the path's weight is made NaN.
GONIO_INLINE void trace_and_book(vec3 travel, INOUT(Rng) rng, uint max_events, INOUT(Tally) t, uint staging_base,
                                 bool poison) {
    if (!(ENTRY_BRANCH && SPECIALISED && !SERIES) && !exit_estimate_applies()) {
        PathResult r = trace_path(travel, rng, max_events);
        if (poison) r.weight.x = uintBitsToFloat(0x7fc00000u);
        tally_path(t, r, rng, staging_base);
        return;
    }
    Walk p;
    PathResult r;
    walk_begin(p, r, travel);
    vec4 reflected = vec4(0.0f);
    vec3 arrival = vec3(0.0f);
    vec3 arrival_w = vec3(0.0f);
    uint arrival_cls = 0u;
    uint direct_outcome;
    uint reversals_estimated =
        trace_first_step(p, r, rng, max_events, reflected, arrival, arrival_w, arrival_cls, direct_outcome);
    Rng e = side_stream(rng);
    // the entry's reflected branch: a direct reflection, class 0
    float heavy = FAULT_FOR_TESTS == FAULT_ENTRY_BRANCH_HEAVY ? 1.02f : 1.0f;
    Booking entry = held_booking(reflected.w != 0.0f, vec3(reflected.w * heavy),
                                 vec3(reflected.x, reflected.y, reflected.z), 0u, 0u, t);
    for (uint it = 1u; it < max_events; ++it)
        if (!(p.alive && r.events < max_events) || !walk_step(p, r, rng, max_events)) break;
    walk_finish(p, r);
    // the path's own exit right after the estimated base event is one of the direct exit's estimates
    bool estimated = reversals_estimated != 0xffffffffu;
    bool direct = r.outcome == direct_outcome && p.reversals == reversals_estimated;
    float share = exit_estimate_share();
    r.absorbed += direct ? (1.0f - share) * r.weight : vec3(0.0f);
    r.weight = direct ? share * r.weight : r.weight;
    if (poison) r.weight.x = uintBitsToFloat(0x7fc00000u);
    book_path_and_estimates(t, r, entry, estimated, arrival, arrival_w, arrival_cls, rng, e, staging_base);
}
#endif
