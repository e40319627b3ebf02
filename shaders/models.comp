#version 450
// models.comp: bin averages of an analytic layered model on the reference's bins, reflection side, or
// transmission side (side = 1) for models with a transmitted lobe, whose lobe grid is the reflection grid
// mirrored through the surface plane.
// A bin's value is (1/Omega) * integral over the bin of f(l, v) cos(theta_v) dv, never a bin-centre sample.
//   KERNEL 0 (graded quadrature): one invocation per bin, Gauss-Legendre on pieces of the bin refined towards the
//            lobes' peak (the mirror direction), the horizon and breaks, with the lobe mapped to cos^2 next to
//            its peak (quad_piece_step below); a 4 x 4 and a 3 x 3 rule per piece pair, their difference the
//            error estimate. Every term that is not a delta, unless float cannot resolve it in v (below).
//   KERNEL 1 (lobe grid): a G x G grid of visible-normal samples around the mirror direction (of l, or of l
//            refracted into the coat for a base lobe at refracted directions): each node adds its weight to a bin
//            (64-bit fixed point). For a delta lobe (roughness 0, evaluated at 1e-4) all of it goes to the bin of
//            the mirror direction. For a lobe narrower in v than float resolves (host/models/model_plan.h
//            kFloatUnresolved: a 1e-4 lobe beyond 84 degrees), each node to the bin its direction falls in, on
//            two grids, the lobe's own and a wide one (0.5, half the nodes per side), combined by the balance
//            heuristic with the sample counts, so that the tails are integrated as well as the peak.
//   KERNEL 2 (pre-pass): Belcour's and tm21's lobes, once per dispatch.
//   KERNEL 3 (points): a user's model at given direction pairs, which gonio swaps to measure its reciprocity.
// host/models/model_plan.cpp plan() chooses, per term and incident angle; docs/MODELS.md "Bin integration".
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#include "compat.glsl"
#include "kernel_interface.glsl"
#include "stack_params.glsl"
#include "bins.glsl"

layout(local_size_x = MODEL_GROUP_SIZE) in;
layout(constant_id = MODEL_SPEC_KERNEL) const uint KERNEL = 0u;
// The model, specialised per pipeline: each pipeline carries one model's code only (one uber-shader with every
// model ran every model 5x slower on lavapipe, measured).
layout(constant_id = MODEL_SPEC_MODEL) const uint MODEL = 0u;
// Its conventions (CONVENTION_* bits, models/belcour_tables.glsl): a registry variant such as
// belcour18-forward+g2 is the same model's module specialised with other bits.
layout(constant_id = MODEL_SPEC_CONVENTION) const uint CONVENTION = 0u;
// Whether the bins are those of an incident azimuth (kernel_interface.glsl ModelPush phi_shift): the kernels work in
// the incident frame, l in the plane xz as at phi_i = 0, and turn l and v into the surface's frame for the model
layout(constant_id = MODEL_SPEC_INCIDENT_AZIMUTH) const bool INCIDENT_AZIMUTH = false;

layout(std140, set = 0, binding = MODEL_BINDING_STACK) uniform StackBlock { StackGpu u_stack; };   // stack_params.glsl
layout(std430, set = 0, binding = MODEL_BINDING_QUADRATURE) buffer Quadrature { QuadBin quad[]; };   // KERNEL 0's output
layout(std430, set = 0, binding = MODEL_BINDING_LOBE_SUMS) buffer LobeSums { int64_t lobe[]; };      // per bin: RGB, units 2^-59
// the models' per-stack tables (kernel_interface.glsl STACK_TABLE_*)
layout(std430, set = 0, binding = MODEL_BINDING_STACK_TABLES) readonly buffer StackTables { float stack_tables[]; };
layout(std430, set = 0, binding = MODEL_BINDING_BELCOUR_TABLES) readonly buffer BelcourTables { float belcour_tables[]; };   // FGD, TIR
layout(std430, set = 0, binding = MODEL_BINDING_BELCOUR_LOBES) buffer BelcourLobeBuffer { vec4 belcour_lobe_buf[]; };   // KERNEL 2's output

layout(push_constant) uniform PushBlock { ModelPush pc; };   // kernel_interface.glsl

// What the models read from their environment (the CPU twin provides the same in host/models/model_cpu.cpp).
float model_stack_table(uint i) { return stack_tables[i]; }
uint model_parameter_slot() { return MODEL; }   // a built-in's code, a user's file's slot (the host's MODEL)
uint model_layer_count() { return stack_layer_count(u_stack.info); }
LayerGpu model_layer(uint i) { return u_stack.layers[i]; }
bool model_use_tables() { return pc.use_tables != 0u; }
float model_table(uint i) { return belcour_tables[i]; }
uint model_convention() { return CONVENTION; }
#define BELCOUR_PRECOMPUTED_LOBES 1
vec4 model_lobe(uint k) { return belcour_lobe_buf[k]; }
void model_lobe_store(uint k, vec4 x) { belcour_lobe_buf[k] = x; }
float model_mu_jump() { return pc.mu_jump; }

// A direction of the incident frame in the surface's (turned by phi_i about z), and back; without an azimuth the
// frames are one
vec3 to_surface_frame(vec3 d) {
    return INCIDENT_AZIMUTH ? vec3(pc.cos_pi * d.x - pc.sin_pi * d.y, pc.sin_pi * d.x + pc.cos_pi * d.y, d.z) : d;
}
vec3 to_incident_frame(vec3 d) {
    return INCIDENT_AZIMUTH ? vec3(pc.cos_pi * d.x + pc.sin_pi * d.y, pc.cos_pi * d.y - pc.sin_pi * d.x, d.z) : d;
}

#ifdef GONIO_USER_MODEL
#include "models/user_model.glsl"   // a model file compiled at run time (host/models/user_model.cpp)
#else
#include "models/all.glsl"
#include "models/belcour18.glsl"   // the pre-pass's lobes (BelcourLobes, KERNEL 2) for every model's module
#endif

// ---- KERNEL 0: graded Gauss-Legendre quadrature per bin ------------------------------------------------------
// Each bin is cut in theta and in phi into pieces refined geometrically (ratio 2) towards "attractors": the lobes'
// peak (every lobe of these models is centred on the mirror direction, or the straight-through one for a
// transmitted lobe) with the narrowest lobe's width there, the horizon (masking), and breaks (a critical angle).
// A piece next to an attractor at c of width w is integrated in s = atan((x - c) / w): a GGX lobe, which falls as
// (1 + (x / w)^2)^-2 along each coordinate, becomes cos^2(s) there, smooth at any width, so a 1e-4 lobe is
// resolved by its first pieces (within 2w, 4w, 8w, ...) and its tails by the ones beyond, each piece as long as its
// distance from the peak. 4 x 4 Gauss-Legendre nodes per piece pair (exact for polynomials of degree 7).
const float GL4_X[4] = float[4](-0.861136311594053f, -0.339981043584856f, 0.339981043584856f, 0.861136311594053f);
const float GL4_W[4] = float[4](0.347854845137454f, 0.652145154862546f, 0.652145154862546f, 0.347854845137454f);
// 3-point Gauss-Legendre on the same pieces, for the error estimate
const float GL3_X[3] = float[3](-0.774596669241483f, 0.0f, 0.774596669241483f);
const float GL3_W[3] = float[3](0.555555555555556f, 0.888888888888889f, 0.555555555555556f);

// The step from x towards b allowed by attractor (c, w) (w = 0: none): the distance to it while that is under
// twice its width, else half the distance (so the pieces halve towards it and land on it), and on the far side the
// distance already covered (pieces double away from it), never below w.
// Within a width of the attractor the pieces are w / pc.refine long (refine >= 1, see the push constants).
float quad_attract(float x, float c, float w) {
    if (!(w > 0.0f)) return 1e30f;
    float d = c - x, wr = w / pc.refine;
    if (d > 1e-6f) return d <= wr ? d : max(wr, 0.5f * d);
    return max(wr, -d);
}
#ifdef GONIO_MODEL_HINTS
// A user's model's lobe hints (models/user_model.glsl, model_lobes) as further attractors, set per bin in main:
// theta (dimension 0: [k]) and phi as offsets from pi (dimension 1: [GONIO_MAX_LOBES + k]); hint_n of them
uint hint_n = 0u;
float hint_c[2u * GONIO_MAX_LOBES], hint_w[2u * GONIO_MAX_LOBES];
#endif
// dim: 0 theta, 1 phi (which of the hints' attractors apply)
float quad_piece_step(float x, float b, float c0, float w0, float c1, float w1, float c2, float w2, float smax,
                      uint dim) {
    float s =
        min(min(b - x, smax), min(quad_attract(x, c0, w0), min(quad_attract(x, c1, w1), quad_attract(x, c2, w2))));
#ifdef GONIO_MODEL_HINTS
    // constant bounds (GONIO_MAX_LOBES), which the compiler can unroll
    for (uint k = 0u; k < GONIO_MAX_LOBES; ++k)
        if (k < hint_n) s = min(s, quad_attract(x, hint_c[dim * GONIO_MAX_LOBES + k], hint_w[dim * GONIO_MAX_LOBES + k]));
#endif
    if (b - (x + s) < 0.25f * s) s = b - x;   // no sliver at the bin's edge
    return max(s, min(1e-6f, b - x));   // progress in float (widths are at least 1e-6, host/models/model_evaluator.cpp)
}
// A piece [x0, x1] and how its nodes are placed: offsets o from the anchor c, either linear (c = x0) or
// o = w tan(s), s uniform in [s0, s1] (the attractor nearest relative to its width).
struct QuadPiece { float c, w, s0, s1; bool mapped; };
// Attractor (c, w) for piece [x0, x1] if it is nearer, relative to its width, than `best` (quad_piece)
void quad_piece_consider(inout QuadPiece q, inout float best, float x0, float x1, float c, float w) {
    if (!(w > 0.0f) || w > 1.0f) return;
    // pieces cut to 1/split of the bin (a black box's refinement) shorter than the attractor's width: the lobe is
    // smooth across them, and s1 - s0 far out in the map (s near pi/2) keeps few digits of their length (3e-4
    // of a constant's bin average measured at 10 degrees, theta_i 60, alpha 0.1)
    if (pc.split > 1u && x1 - x0 < w) return;
    // distance from the attractor to the piece (0 when it is inside: the pieces land on attractors, but one
    // within float rounding of an edge, e.g. the peak at theta_i = 89 degrees on a bin edge, is not landed on;
    // the map is monotonic across c, so a piece may hold it)
    float d = max(0.0f, max(x0 - c, c - x1));
    if (d / w >= best) return;
    best = d / w;
    q.c = c; q.w = w; q.s0 = atan((x0 - c) / w); q.s1 = atan((x1 - c) / w); q.mapped = true;
}
QuadPiece quad_piece(float x0, float x1, float c0, float w0, float c1, float w1, uint dim) {
    QuadPiece q;
    q.c = x0; q.w = x1 - x0; q.s0 = 0.0f; q.s1 = 1.0f; q.mapped = false;
    // within 4 widths of an attractor: mapped; farther, the pieces (at most twice as far out as in) are smooth
    // enough for the linear rule, and s would be near pi/2, where float loses the piece's length (s1 - s0)
    float best = 4.0f;
    quad_piece_consider(q, best, x0, x1, c0, w0);
    quad_piece_consider(q, best, x0, x1, c1, w1);
#ifdef GONIO_MODEL_HINTS
    for (uint k = 0u; k < GONIO_MAX_LOBES; ++k)
        if (k < hint_n)
            quad_piece_consider(q, best, x0, x1, hint_c[dim * GONIO_MAX_LOBES + k], hint_w[dim * GONIO_MAX_LOBES + k]);
#endif
    return q;
}
// Node a of a piece (rule 4: 0..3, GL4_X; rule 3: 0..2, GL3_X): offset o from the anchor and the Jacobian
// times the half-length (weights GL4_W or GL3_W).
void quad_node(QuadPiece q, uint rule, uint a, OUT(float) o, OUT(float) jac) {
    float h = 0.5f * (q.s1 - q.s0), s = q.s0 + h * (1.0f + (rule == 4u ? GL4_X[a] : GL3_X[a]));
    if (q.mapped) {
        float ts = tan(s);
        o = q.w * ts;
        jac = q.w * (1.0f + ts * ts) * h;
    } else {
        o = q.w * s;
        jac = q.w * h;
    }
}


#ifndef GONIO_USER_MODEL
// ---- KERNEL 2: Belcour's (or tm21's) lobes, once per dispatch -------------------------------------------------
// forward, top-lobe and tm21 at mu = cos theta_i (one invocation), the symmetric variant at BELCOUR_MU_NODES nodes of
// mu = |h.l| (quadratic in mu: fine towards grazing); the model's file's hooks (models/all.glsl: GONIO_MODEL_LOBES,
// GONIO_MODEL_LOBE_TABLE)
void lobes_kernel(vec3 l) {
    uint node = gl_GlobalInvocationID.x;
#ifdef GONIO_MODEL_LOBE_TABLE
    bool symmetric = true;
#else
    bool symmetric = false;
#endif
    if (node >= (symmetric ? BELCOUR_MU_NODES : 1u)) return;
    float mu = symmetric ? belcour_mu_node(node) : l.z;
    model_store_lobes(node, model_lobes_at(mu));
}
#endif

// ---- KERNEL 0: the graded quadrature of one bin ----------------------------------------------------------------
// A bin: theta in [ta, tb], phi in offsets [pa, pb] from the plane of incidence's far side (phi = pi), where every
// lobe peaks.
struct QuadBox { float ta, tb, pa, pb; };

// Fresnel reflection from a denser exterior reaches 1 with a square-root kink where l.h crosses the critical cosine
// (total internal reflection), on a curve through the bins (l.v = 2 cos_kink^2 - 1); the lobes of Belcour's
// symmetric variant (from mu = |h.l|) jump there. A bin the curve crosses (its corners on both sides) gets pieces of
// at most 1/8 of its side: the error of a square-root kink falls as pieces^-1.5. Also a black box refined where its
// nodes disagreed: pieces of at most 1/split of the bin.
void quad_max_pieces(QuadBox q, vec3 l, OUT(float) smt, OUT(float) smp) {
    smt = 1e30f;
    smp = 1e30f;
    if (pc.cos_kink > 0.0f) {
        float lv0 = 2.0f * pc.cos_kink * pc.cos_kink - 1.0f, lo = 2.0f, hi = -2.0f;
        for (uint k = 0u; k < 9u; ++k) {
            float th = mix(q.ta, q.tb, 0.5f * float(k % 3u)), ph = PI + mix(q.pa, q.pb, 0.5f * float(k / 3u));
            // l.y = 0; the side's sign of v.z: l.v of the mirrored v
            float lv = sin(th) * cos(ph) * l.x + cos(th) * l.z;
            if (pc.side != 0u) lv = sin(th) * cos(ph) * l.x - cos(th) * l.z;
            lo = min(lo, lv); hi = max(hi, lv);
        }
        if (lo < lv0 && lv0 < hi) { smt = 0.125f * (q.tb - q.ta); smp = 0.125f * (q.pb - q.pa); }
    }
    if (pc.split > 1u) {
        smt = min(smt, (q.tb - q.ta) / float(pc.split));
        smp = min(smp, (q.pb - q.pa) / float(pc.split));
    }
}

#ifdef GONIO_MODEL_HINTS
// A user's model's lobes for light from l on this side (a lobe with direction.z < 0 is on the transmission side) as
// attractors (hint_c, hint_w): theta at its polar angle, 2 alpha wide as the peak; phi at its azimuth (the copy
// nearest the bin), as wide as a GGX lobe reflected at that polar angle (as wp); a delta lobe is booked, not
// integrated. Returns QUAD_HINTS_* flags.
uint quad_hints(QuadBox q, vec3 l) {
    bool hints_bad = false, hint_unresolved = false;
    GonioLobe hl[GONIO_MAX_LOBES];   // an out parameter: only the first nh are read
    uint nh = model_lobes(to_surface_frame(l), hl);   // the lobes in the surface's frame
    hints_bad = nh > GONIO_MAX_LOBES;
    hint_n = 0u;
    uint deltas = 0u;
    // the first invocation of a dispatch over every bin books the delta lobes for the host: lobes[0].x their count,
    // lobes[1 + k] = (weight, the bin of the direction, as the lobe grid bins a delta: KERNEL 1)
    bool book = gl_GlobalInvocationID.x == 0u && pc.bin_first == 0u;
    for (uint k = 0u; k < GONIO_MAX_LOBES; ++k) {
        if (k >= nh) continue;
        vec3 d = hl[k].direction, d0 = d;
        float a = hl[k].roughness;
        if (any(isnan(d)) || any(isinf(d)) || !(length(d) > 0.0f) || !(a >= 0.0f) || isinf(a)) {
            hints_bad = true;
            continue;
        }
        d = to_incident_frame(normalize(d));   // as the pieces are laid out
        if ((d.z < 0.0f) != (pc.side != 0u)) continue;
        if (a == 0.0f) {   // a delta lobe: not in f, its weight booked whole by the host
            vec3 wd = hl[k].weight;
            if (any(isnan(wd)) || any(isinf(wd)) || any(lessThan(wd, vec3(0.0f)))) {
                hints_bad = true;
                continue;
            }
            // binned as given, in the surface's frame (a mirror direction (-l.x, -l.y, l.z) as KERNEL 1 bins a
            // built-in's delta)
            uint db = bin_index(vec3(d0.xy, abs(d0.z)), 0u, 0u, 1u, pc.n_theta, pc.n_phi, 1.0f / pc.dtheta,
                                1.0f / pc.dphi);
            if (book) belcour_lobe_buf[1u + deltas] = vec4(wd, float(db));
            ++deltas;
            continue;
        }
        float al = max(a, MODEL_MIN_ALPHA), th = atan(length(d.xy), abs(d.z));
        // narrower in v than float resolves (MODEL_FLOAT_UNRESOLVED): the quadrature cannot integrate it
        if (2.0f * al * abs(d.z) < MODEL_FLOAT_UNRESOLVED) hint_unresolved = true;
        float ph = atan(d.y, d.x) - PI, mid = 0.5f * (q.pa + q.pb);
        ph += 2.0f * PI * round((mid - ph) / (2.0f * PI));
        hint_c[hint_n] = th;
        hint_w[hint_n] = 2.0f * al;
        hint_c[GONIO_MAX_LOBES + hint_n] = ph;
        hint_w[GONIO_MAX_LOBES + hint_n] = sin(th) > 1e-6f ? al * (cos(th) + cos(q.tb)) / max(sin(q.tb), 1e-6f) : 0.0f;
        ++hint_n;
    }
    if (book) belcour_lobe_buf[0] = vec4(float(deltas), 0.0f, 0.0f, 0.0f);
    return (hints_bad ? QUAD_HINTS_UNUSABLE : 0u) + (hint_unresolved ? QUAD_HINTS_UNRESOLVED : 0u);
}
#endif

// Belcour's symmetric variant reads its lobes from a table in mu = |h.l| (belcour18.glsl), which cannot follow the
// lobes next to the jump at mu_jump (they change like a square root there): bins whose mu comes within two node
// intervals of it evaluate the adding loop itself
bool quad_exact(QuadBox q, vec3 l) {
    bool exact = false;
#ifdef GONIO_MODEL_EXACT
    if (pc.mu_jump > 0.0f) {
        float xj = sqrt(pc.mu_jump) * float(BELCOUR_MU_NODES - 1u);
        float lo = 2.0f, hi = -2.0f;
        for (uint k = 0u; k < 9u; ++k) {
            float th = mix(q.ta, q.tb, 0.5f * float(k % 3u)), ph = PI + mix(q.pa, q.pb, 0.5f * float(k / 3u));
            float lv = sin(th) * cos(ph) * l.x + cos(th) * l.z;
            // the table's node coordinate
            float x = sqrt(sqrt(max(0.5f * (1.0f + lv), 0.0f))) * float(BELCOUR_MU_NODES - 1u);
            lo = min(lo, x); hi = max(hi, x);
        }
        exact = lo < xj + 2.0f && hi > xj - 2.0f;
    }
#endif
    return exact;
}

// The model's value at v (l and v in the incident frame, the model's in the surface's), or where the symmetric
// variant's table cannot follow its lobes, the adding loop's
vec3 quad_model(CoatParams p, bool exact, vec3 l, vec3 v) {
    vec3 ls = to_surface_frame(l), vs = to_surface_frame(v);
#ifdef GONIO_MODEL_EXACT
    return exact ? GONIO_MODEL_EXACT(pc.terms, ls, vs) : eval_model(MODEL, p, pc.terms, ls, vs);
#else
    return eval_model(MODEL, p, pc.terms, ls, vs);
#endif
}

// The attractors (see quad_piece_step above): theta: the peak (theta_i, width 2 alpha), the horizon (the GGX
// masking of v falls to 0 within ~alpha of it), a discontinuity (the critical angle: a break, no grading); phi: the
// peak, whose width across the plane of incidence is alpha (cos theta_i + cos theta) / sin theta (the half vector's
// tilt out of the plane is alpha h.z over the projected distance (l + v).xy: docs/MODELS.md), smallest at the bin's
// upper theta edge.
struct QuadAttractors { float theta_p, wt, wh, wp, cb, wb, smt, smp; };

// At most max_rects piece pairs (the loop limiter, header): coarser grading where more would be needed. Returns
// nt x np.
uint quad_grade(QuadBox q, INOUT(QuadAttractors) at) {
    const float HALF_PI = 1.57079632679f;
    uint nt = 0u, np = 0u;
    for (int pass = 0; pass < 16; ++pass) {
        nt = 0u;
        for (float x = q.ta; x < q.tb; ++nt)
            x += quad_piece_step(x, q.tb, at.theta_p, at.wt, HALF_PI, at.wh, at.cb, at.wb, at.smt, 0u);
        np = 0u;
        for (float x = q.pa; x < q.pb; ++np) x += quad_piece_step(x, q.pb, 0.0f, at.wp, 0.0f, 0.0f, 0.0f, 0.0f, at.smp, 1u);
        if (nt * np <= pc.max_rects) break;
        at.wt *= 2.0f; at.wh *= 2.0f; at.wp *= 2.0f;
#ifdef GONIO_MODEL_HINTS
        for (uint k = 0u; k < 2u * GONIO_MAX_LOBES; ++k) hint_w[k] *= 2.0f;
#endif
    }
    return nt * np;
}

// The sum over the bin's piece pairs of f cos(theta) sin(theta) dtheta dphi by the 4 x 4 rule (acc) and the
// difference to the 3 x 3 rule on the same pieces (err); bad: nodes where the model returned NaN, an infinity or a
// negative value.
void quad_integrate(CoatParams p, vec3 l, QuadBox q, QuadAttractors at, bool exact, OUT(vec3) acc, OUT(vec3) err,
                    OUT(uint) bad) {
    const float HALF_PI = 1.57079632679f;
    acc = vec3(0.0f);
    err = vec3(0.0f);
    bad = 0u;
    for (float x0 = q.ta; x0 < q.tb;) {
        float x1 = x0 + quad_piece_step(x0, q.tb, at.theta_p, at.wt, HALF_PI, at.wh, at.cb, at.wb, at.smt, 0u);
        QuadPiece qt = quad_piece(x0, x1, at.theta_p, at.wt, HALF_PI, at.wh, 0u);
        float sct = sin(qt.c), cct = cos(qt.c);
        for (float y0 = q.pa; y0 < q.pb;) {
            float y1 = y0 + quad_piece_step(y0, q.pb, 0.0f, at.wp, 0.0f, 0.0f, 0.0f, 0.0f, at.smp, 1u);
            QuadPiece qp = quad_piece(y0, y1, 0.0f, at.wp, 0.0f, 0.0f, 1u);
            float scp = sin(qp.c), ccp = cos(qp.c);
            // the 4 x 4 rule, then the 3 x 3 rule on the same piece pair: their difference estimates the error
            vec3 pair4 = vec3(0.0f), pair3 = vec3(0.0f);
            for (uint rule = 4u; rule >= 3u; --rule) {
                vec3 sum = vec3(0.0f);
                for (uint a = 0u; a < rule; ++a) {
                    float ot, jt;
                    quad_node(qt, rule, a, ot, jt);
                    float so = sin(ot), co = cos(ot);
                    float st = sct * co + cct * so, ct = cct * co - sct * so;   // sin, cos of c + o
                    if (!(ct > 0.0f)) continue;
                    float wa = rule == 4u ? GL4_W[a] : GL3_W[a];
                    for (uint c = 0u; c < rule; ++c) {
                        float op, jp;
                        quad_node(qp, rule, c, op, jp);
                        float sq = sin(op), cq = cos(op);
                        // phi = pi + c + o
                        float cp = -(ccp * cq - scp * sq), sp = -(scp * cq + ccp * sq);
                        vec3 v = vec3(st * cp, st * sp, pc.side != 0u ? -ct : ct);
                        vec3 fm = quad_model(p, exact, l, v);
                        if (any(isnan(fm)) || any(isinf(fm)) || any(lessThan(fm, vec3(0.0f)))) ++bad;
                        sum += fm * (ct * st * jt * jp * wa * (rule == 4u ? GL4_W[c] : GL3_W[c]));
                    }
                }
                if (rule == 4u) pair4 = sum; else pair3 = sum;
            }
            acc += pair4;
            err += abs(pair4 - pair3);
            y0 = y1;
        }
        x0 = x1;
    }
}

// Graded Gauss-Legendre quadrature of bin bin_first + invocation (see quad_piece_step above): theta pieces x phi
// pieces, 4 x 4 nodes each, cos(theta) sin(theta) dtheta dphi; the bin average is the sum over Omega.
void quadrature_kernel(CoatParams p, vec3 l) {
    uint b = gl_GlobalInvocationID.x + pc.bin_first;
    if (b >= pc.n_theta * pc.n_phi) return;
    uint t = b / pc.n_phi, j = b - t * pc.n_phi;
    const float HALF_PI = 1.57079632679f;
    QuadBox q;
    q.ta = float(t) * pc.dtheta;
    q.tb = min(float(t + 1u) * pc.dtheta, HALF_PI);
    q.pa = (float(j) - 0.5f) * pc.dphi - PI;
    // at an azimuth, the surface's bin j in the incident frame: centred on (j - phi_shift) dphi - phi_rest
    if (INCIDENT_AZIMUTH) q.pa = (float((j + pc.n_phi - pc.phi_shift) % pc.n_phi) - 0.5f) * pc.dphi - PI - pc.phi_rest;
    q.pb = q.pa + pc.dphi;
    QuadAttractors at;
    at.theta_p = atan2(pc.sin_ti, pc.cos_ti);
    at.wt = pc.w_theta;
    at.wh = pc.w_horizon;
    at.wp = pc.a_phi > 0.0f ? pc.a_phi * (pc.cos_ti + cos(q.tb)) / max(sin(q.tb), 1e-6f) : 0.0f;
    at.cb = pc.theta_break;
    at.wb = pc.theta_break > 0.0f ? 1e30f : 0.0f;   // a break
    quad_max_pieces(q, l, at.smt, at.smp);
    uint hint_flags = 0u;
#ifdef GONIO_MODEL_HINTS
    hint_flags = quad_hints(q, l);
#endif
    bool exact = quad_exact(q, l);
    uint pairs = quad_grade(q, at);
    vec3 acc, err;
    uint bad;
    quad_integrate(p, l, q, at, exact, acc, err, bad);
    // lavapipe's loop limiter (docs/ARCHITECTURE.md) is one count for every loop of the invocation: once it ran out,
    // every loop ends at its first test, this one too, so a probe that makes fewer trips than asked says that the
    // loops above were cut short (no real GPU has the limiter: the probe always completes there)
    uint probe = 0u;
    for (uint k = 0u; k < pc.n_theta; ++k) ++probe;
    // the bin's projected solid angle (sin^2 tb - sin^2 ta) dphi / 2, as sin(tb - ta) sin(tb + ta): the difference of
    // squares keeps few digits next to the horizon in float (2e-4 of the 89-90 degree bin)
    float omega = 0.5f * sin(q.tb - q.ta) * sin(q.tb + q.ta) * pc.dphi;
    acc /= omega;
    err /= omega;
    QuadBin o;
    o.f[0] = acc.x; o.f[1] = acc.y; o.f[2] = acc.z;
    o.nodes = probe == pc.n_theta ? float(25u * pairs) : -1.0f;   // -1: cut short
    o.err[0] = err.x; o.err[1] = err.y; o.err[2] = err.z;
    o.bad = float(bad);
    o.hint_flags = float(hint_flags);
    quad[b] = o;
}

// ---- KERNEL 1: a visible-normal lobe grid ----------------------------------------------------------------------
// The grid's own frame: l, or l refracted into the coat (a base lobe at Snell-refracted directions, which seen from
// outside is stretched in theta by eta cos(theta1) / cos(theta), 60x at 89 degrees: a grid drawn outside would miss
// most of it). Directions drawn inside are refracted out, dv = eta^2 cos(theta1) / cos(theta) dv1, so the weight
// f cos(theta) dv / pdf(v1) dv1 is f eta^2 cos(theta1) / pdf(v1).
void lobe_grid_kernel(CoatParams p, vec3 l) {
    uint first = gl_GlobalInvocationID.x * LOBE_GRID_NODES_PER_INVOCATION;
    float inv_c = 1.0f / float(pc.grid), inv_r = 1.0f / float(pc.grid_rows);
    const bool inside = pc.grid_eta > 0.0f;
    vec3 lg = inside ? refract_into_coat(l, pc.grid_eta) : l;
    if (inside && lg.z <= 1e-6f) return;   // l totally reflected at the coat: nothing enters
    for (uint i = first; i < first + LOBE_GRID_NODES_PER_INVOCATION; ++i) {
        if (i >= pc.grid * pc.grid_rows) break;
        uint gy = i / pc.grid, gx = i - gy * pc.grid;
        vec3 m = sample_ggx_visible_normal(lg, pc.alpha_grid, (float(gx) + 0.5f) * inv_c, (float(gy) + 0.5f) * inv_r);
        vec3 vg = reflect_about(lg, m);
        if (vg.z <= 0.0f) continue;
        float pdf = ggx_visible_normal_pdf(lg, m, pc.alpha_grid) / (4.0f * dot(lg, m));
        if (!(pdf > 0.0f)) continue;
        // two grids per lobe, its own and a wide one, combined by the balance heuristic (Veach 1997): the narrow
        // grid carries the peak, the wide one the tails, where the narrow grid's nodes are sparse
        float partner =
            pc.alpha_partner > 0.0f ? ggx_visible_normal_pdf(lg, m, pc.alpha_partner) / (4.0f * dot(lg, m)) : 0.0f;
        // balance heuristic over grids of different sizes: f / (N_own pdf_own + N_partner pdf_partner)
        float denom = pdf * float(pc.grid * pc.grid_rows) + partner * float(pc.partner_nodes);
        vec3 v = vg;
        float cosw = vg.z;   // cos(theta) dv / dv_grid
        if (inside) {
            vec2 t = vg.xy * pc.grid_eta;
            float s2 = dot(t, t);
            if (s2 >= 1.0f) continue;   // beyond the critical angle: does not leave the coat
            v = vec3(t, sqrt(1.0f - s2));
            cosw = pc.grid_eta * pc.grid_eta * vg.z;
        }
        vec3 vs = to_surface_frame(pc.side != 0u ? vec3(v.x, v.y, -v.z) : v);   // the model's and the bins' frame
        vec3 w = eval_model(MODEL, p, pc.terms, to_surface_frame(l), vs) * (cosw / denom);
        vec3 binned = to_surface_frame(pc.delta != 0u ? vec3(-l.x, -l.y, l.z) : v);
        uint bin = bin_index(binned, 0u, 0u, 1u, pc.n_theta, pc.n_phi, 1.0f / pc.dtheta, 1.0f / pc.dphi);
        for (uint c = 0u; c < CHANNELS; ++c) {
            int64_t qv = int64_t(round(w[c] * LOBE_SCALE));
            if (qv != 0l) atomicAdd(lobe[bin * LOBE_SUMS_PER_BIN + c], qv);
        }
    }
}

#ifdef GONIO_USER_MODEL
// ---- KERNEL 3: a user's model at given direction pairs ------------------------------------------------------------
// The lobe binding holds the pairs in and the values out (a user's model has no pre-pass lobes; the host binds a
// buffer of its own there): pair k's l in [2k].xyz, v in [2k + 1].xyz; f(l, v) replaces [2k + 1].xyz, as computed
// (a NaN stays one: the host reports it)
void points_kernel(CoatParams p) {
    uint k = gl_GlobalInvocationID.x;
    if (2u * k + 1u >= uint(belcour_lobe_buf.length())) return;
    vec3 l = belcour_lobe_buf[2u * k].xyz, v = belcour_lobe_buf[2u * k + 1u].xyz;
    belcour_lobe_buf[2u * k + 1u] = vec4(eval_model(MODEL, p, TERM_ALL, l, v), 0.0f);
}
#endif

// One of the kernels, by the pipeline's specialisation (KERNEL)
void main() {
    CoatParams p = coat_params(u_stack.layers[0], u_stack.layers[1]);
    // l in the incident frame (the plane xz), which the kernels turn by phi_i into the surface's (to_surface_frame)
    vec3 l = incident_direction_in_plane(pc.sin_ti, pc.cos_ti);
#ifndef GONIO_USER_MODEL
    if (KERNEL == MODEL_KERNEL_LOBES) {
        lobes_kernel(l);
        return;
    }
#endif
#ifdef GONIO_USER_MODEL
    if (KERNEL == MODEL_KERNEL_POINTS) {
        points_kernel(p);
        return;
    }
#endif
    if (KERNEL == MODEL_KERNEL_QUADRATURE)
        quadrature_kernel(p, l);
    else
        lobe_grid_kernel(p, l);
}
