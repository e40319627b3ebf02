#version 450
// models.comp: bin averages of an analytic layered model on the reference's bins, reflection side, or
// transmission side (side = 1) for models with a transmitted lobe, whose lobe grid is the reflection grid
// mirrored through the surface plane.
// A bin's value is (1/Omega) * integral over the bin of f(l, v) cos(theta_v) dv, never a bin-centre sample.
//   KERNEL 0 (quadrature): one invocation per bin, K x K midpoint nodes in (theta, phi), for the terms
//            that are smooth at the bin scale;
//   KERNEL 1 (lobe grid): for a narrow lobe (its width, squeezed to 2 alpha cos(theta_i) across the plane of
//            incidence at grazing incidence, below 0.03; down to 1e-4), a G x G grid of visible-normal samples
//            around the mirror direction (of l, or of l refracted into the coat for a base lobe at refracted
//            directions): each node adds its weight to the bin its direction falls in (64-bit fixed point),
//            which integrates lobes far narrower than a bin. Each lobe is integrated on two grids, its own
//            roughness and a wide one (0.5, half the nodes per side), combined by the balance heuristic with
//            the sample counts, so that the tails far from the peak are integrated as well as the peak.
//   KERNEL 2 (pre-pass): Belcour's and tm21's lobes, once per dispatch.
// host/models.cpp plan() chooses, per term and incident angle; docs/MODELS.md "Bin integration".
//            A delta lobe (roughness 0) is integrated the same way at roughness 1e-4, for its mass, and all of
//            it goes to the bin of the mirror direction (a GGX tail at 1e-4 would leak 5e-4 of it next door).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint KERNEL = 0u;
// The model, specialised per pipeline: each pipeline carries one model's code only (one uber-shader with every
// model ran every model 5x slower on lavapipe, measured).
layout(constant_id = 1) const uint MODEL = 0u;
// Its conventions (CONVENTION_* bits, models/belcour_tables.glsl): a registry variant such as
// belcour18-forward+g2 is the same model's module specialised with other bits.
layout(constant_id = 2) const uint CONVENTION = 0u;

#include "compat.glsl"
#include "stack_params.glsl"
#include "bins.glsl"

layout(std140, set = 0, binding = 0) uniform StackBlock {
    LayerGpu layers[MAX_LAYERS];
    vec4 info;
} u_stack;
layout(std430, set = 0, binding = 1) buffer Quadrature { float quad[]; };      // per bin: RGB bin average
layout(std430, set = 0, binding = 2) buffer LobeSums { int64_t lobe[]; };      // per bin: RGB, units 2^-40
layout(std430, set = 0, binding = 3) readonly buffer CoatAlbedo { float coat_albedo[]; };   // E_coat(mu), 65 nodes
layout(std430, set = 0, binding = 4) readonly buffer BelcourTables { float belcour_tables[]; };   // FGD, TIR
layout(std430, set = 0, binding = 5) buffer BelcourLobeBuffer { vec4 belcour_lobe_buf[]; };   // KERNEL 2's output

layout(push_constant) uniform Push {
    uint model;
    uint terms;          // which terms this dispatch integrates (TERM_TOP, TERM_BASE)
    uint n_theta;
    uint n_phi;
    float dtheta;        // radians
    float dphi;
    float sin_ti;
    float cos_ti;
    uint k;              // quadrature nodes per bin side
    uint grid;           // lobe-grid columns (u1: the azimuth of the normal about l)
    float alpha_grid;    // roughness of the visible-normal grid
    uint delta;          // 1: the lobe is a delta (roughness 0): its mass all goes to the mirror direction's bin
    float alpha_partner; // the other grid of the pair (balance heuristic), 0: none
    uint side;           // 0: reflection (v.z > 0), 1: transmission (v.z < 0; lobes are mirrored through z = 0)
    uint use_tables;     // Belcour's models: 1: FGD and TIR tables, 0: Fresnel at the mean cosine, no TIR
    uint partner_nodes;  // nodes of the partner grid (balance heuristic with sample counts)
    float grid_eta;      // > 0: a lobe at Snell-refracted directions: the grid is drawn about the mirror direction of
                         // l refracted into a coat of this relative IOR, and its directions are refracted out
    uint grid_rows;      // lobe-grid rows (u2: the polar angle)
} pc;

// What the models read from their environment (the CPU twin provides the same in host/models.cpp).
// E_coat at cos theta = mu: linear interpolation in the table of mu = i / 64 (host/models.cpp)
float model_coat_albedo(float mu) {
    float x = clamp(mu, 0.0f, 1.0f) * 64.0f;
    uint i = min(uint(x), 63u);
    return mix(coat_albedo[i], coat_albedo[i + 1], x - float(i));
}
uint model_layer_count() { return uint(u_stack.info.x); }
LayerGpu model_layer(uint i) { return u_stack.layers[i]; }
bool model_use_tables() { return pc.use_tables != 0u; }
float model_table(uint i) { return belcour_tables[i]; }
uint model_convention() { return CONVENTION; }
#define BELCOUR_PRECOMPUTED_LOBES 1
vec4 model_lobe(uint k) { return belcour_lobe_buf[k]; }

#include "models/all.glsl"

const float LOBE_SCALE = 1099511627776.0f;   // 2^40

void main() {
    CoatParams p = coat_params(u_stack.layers[0], u_stack.layers[1]);
    vec3 l = vec3(pc.sin_ti, 0.0f, pc.cos_ti);
    if (KERNEL == 2u) {
        // Belcour's (or tm21's) lobes, once per dispatch: forward, top-lobe and tm21 at mu = cos theta_i (one invocation),
        // the symmetric variant at BELCOUR_MU_NODES nodes of mu = |h.l| (quadratic in mu: fine towards grazing)
        uint node = gl_GlobalInvocationID.x;
        bool symmetric = MODEL == MODEL_BELCOUR18_SYMMETRIC;
        if (node >= (symmetric ? BELCOUR_MU_NODES : 1u)) return;
        float mu = symmetric ? belcour_mu_node(node) : l.z;
#if GONIO_HAS_MODEL(7)
        BelcourLobes b = tm21_lobes(mu, model_use_tables());
#elif GONIO_HAS_MODEL(4) || GONIO_HAS_MODEL(5) || GONIO_HAS_MODEL(6)
        BelcourLobes b = belcour_lobes(mu, model_use_tables());
#else
        BelcourLobes b;   // no pre-pass for this model (never dispatched)
        b.count = 0u;
        b.e_t = vec3(0.0f);
        b.alpha_t = 0.0f;
#endif
        uint o = node * BELCOUR_LOBE_STRIDE;
        for (uint k = 0u; k < MAX_LAYERS; ++k)
            belcour_lobe_buf[o + k] = k < b.count ? vec4(b.e[k], b.alpha[k]) : vec4(0.0f);
        belcour_lobe_buf[o + MAX_LAYERS] = vec4(b.e_t, b.alpha_t);
        belcour_lobe_buf[o + MAX_LAYERS + 1u] = vec4(uintBitsToFloat(b.count), 0.0f, 0.0f, 0.0f);
        return;
    }
    if (KERNEL == 0u) {
        uint b = gl_GlobalInvocationID.x;
        if (b >= pc.n_theta * pc.n_phi) return;
        uint t = b / pc.n_phi, j = b - t * pc.n_phi;
        float th0 = float(t) * pc.dtheta, ph0 = (float(j) - 0.5f) * pc.dphi;
        // Fresnel transmission falls steeply towards grazing (T ~ cos theta)
        // (the integrand as cos^2 theta with the cosine weight; the midpoint rule's relative error on it is about
        // 1 / (4 kt^2) in the row at the horizon, 1 / (28 kt^2) in the next): at least 16 nodes in theta beyond 80
        // degrees and 32 in the row at the horizon, whatever k the lobes need (32 in every row beyond 80 degrees
        // was half the quadrature's cost)
        float th1 = th0 + pc.dtheta;
        uint kt = th1 > 1.5621f ? max(pc.k, 32u) : (th1 > 1.3963f ? max(pc.k, 16u) : pc.k);
        vec3 acc = vec3(0.0f);
        // phi nodes by rotation (one sin/cos pair per bin instead of one per node)
        float dp = pc.dphi / float(pc.k);
        float cd = cos(dp), sd = sin(dp);
        float cp0 = cos(ph0 + 0.5f * dp), sp0 = sin(ph0 + 0.5f * dp);
        for (uint a = 0u; a < kt; ++a) {
            float th = th0 + (float(a) + 0.5f) / float(kt) * pc.dtheta;
            float st = sin(th), ct = cos(th);
            float cp = cp0, sp = sp0;
            for (uint c = 0u; c < pc.k; ++c) {
                vec3 v = vec3(st * cp, st * sp, pc.side != 0u ? -ct : ct);
                acc += eval_model(MODEL, p, pc.terms, l, v) * (ct * st);
                float cn = cp * cd - sp * sd;
                sp = sp * cd + cp * sd;
                cp = cn;
            }
        }
        float s0 = sin(th0), s1 = sin(th0 + pc.dtheta);
        float omega = 0.5f * (s1 * s1 - s0 * s0) * pc.dphi;
        acc *= (pc.dtheta / float(kt)) * (pc.dphi / float(pc.k)) / omega;
        quad[b * 3u] = acc.x;
        quad[b * 3u + 1u] = acc.y;
        quad[b * 3u + 2u] = acc.z;
    } else {
        uint first = gl_GlobalInvocationID.x * 16u;
        float inv_c = 1.0f / float(pc.grid), inv_r = 1.0f / float(pc.grid_rows);
        // the grid's own frame: l, or l refracted into the coat (a base lobe at Snell-refracted directions, which
        // seen from outside is stretched in theta by eta cos(theta1) / cos(theta), 60x at 89 degrees: a grid drawn
        // outside would miss most of it). Directions drawn inside are refracted out, dv = eta^2 cos(theta1) /
        // cos(theta) dv1, so the weight f cos(theta) dv / pdf(v1) dv1 is f eta^2 cos(theta1) / pdf(v1).
        const bool inside = pc.grid_eta > 0.0f;
        vec3 lg = inside ? refract_into_coat(l, pc.grid_eta) : l;
        if (inside && lg.z <= 1e-6f) return;   // l totally reflected at the coat: nothing enters
        for (uint i = first; i < first + 16u; ++i) {
            if (i >= pc.grid * pc.grid_rows) break;
            uint gy = i / pc.grid, gx = i - gy * pc.grid;
            vec3 m = sample_ggx_visible_normal(lg, pc.alpha_grid, (float(gx) + 0.5f) * inv_c, (float(gy) + 0.5f) * inv_r);
            vec3 vg = reflect_about(lg, m);
            if (vg.z <= 0.0f) continue;
            float pdf = ggx_visible_normal_pdf(lg, m, pc.alpha_grid) / (4.0f * dot(lg, m));
            if (!(pdf > 0.0f)) continue;
            // two grids per lobe, its own and a wide one, combined by the balance heuristic (Veach 1997): the
            // narrow grid carries the peak, the wide one the tails, where the narrow grid's nodes are sparse
            float partner = pc.alpha_partner > 0.0f ? ggx_visible_normal_pdf(lg, m, pc.alpha_partner) / (4.0f * dot(lg, m)) : 0.0f;
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
            vec3 w = eval_model(MODEL, p, pc.terms, l, pc.side != 0u ? vec3(v.x, v.y, -v.z) : v) * (cosw / denom);
            vec3 binned = pc.delta != 0u ? vec3(-l.x, -l.y, l.z) : v;
            uint bin = bin_index(binned, 0u, 0u, 1u, pc.n_theta, pc.n_phi, 1.0f / pc.dtheta, 1.0f / pc.dphi);
            for (int c = 0; c < 3; ++c) {
                int64_t q = int64_t(round(w[c] * LOBE_SCALE));
                if (q != 0l) atomicAdd(lobe[bin * 3u + uint(c)], q);
            }
        }
    }
}
