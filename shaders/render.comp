#version 450
// render.comp: one analytic model on a sphere under an environment map (gonio render; docs/RENDER.md).
// An orthographic camera looks down -z at a unit sphere filling the frame: at pixel centre (x, y) the normal is
// n = (x, y, sqrt(1 - x^2 - y^2)) and the view direction is v = +z. The sphere is convex and the environment
// distant, so a pixel is exactly the integral over the upper hemisphere of the local frame of
//     L(w) f(w, v) cos(theta_w) dw      (f(l, v): l the light's direction, v the viewer's; cosine excluded)
// estimated with three strategies, one sample of each per iteration, combined by the power heuristic (Veach 1997,
// section 9.2.4): the environment (a CDF over texels of max(luminance - mean, 0) x sin(theta): MIS compensation,
// Karlik et al. 2019; none for a constant map), the cosine hemisphere,
// and a GGX lobe about the mirror direction of v (visible normals, at the top interface's roughness and, over a
// conductor base, half the time at the base's), which finds the smooth interfaces that the models evaluate as
// GGX at 1e-4. The sample points are a rank-1 lattice (R2, Roberts 2018) shifted per pixel and strategy by
// rng.glsl's counter-based numbers: deterministic for a seed, on any dispatch shape.
// The lavapipe loop limiter (65535 loop trips per invocation): a dispatch runs pc.samples iterations only, each
// 3 model evaluations and two binary searches (host/render/model_render.cpp keeps the product far below).
#extension GL_GOOGLE_include_directive : require

#include "compat.glsl"
#include "kernel_interface.glsl"
#include "stack_params.glsl"
#include "rng.glsl"
#include "render_interface.glsl"

layout(local_size_x = RENDER_GROUP_SIZE) in;
// The model, as in models.comp: one module per model (GONIO_MODEL_ONLY), its conventions specialised
layout(constant_id = MODEL_SPEC_MODEL) const uint MODEL = 0u;
layout(constant_id = MODEL_SPEC_CONVENTION) const uint CONVENTION = 0u;

layout(std140, set = 0, binding = RENDER_BINDING_STACK) uniform StackBlock { StackGpu u_stack; };   // stack_params.glsl
layout(std430, set = 0, binding = RENDER_BINDING_ACCUM) buffer Accum { vec4 accum[]; };   // per pixel: RGB sum, -
layout(std430, set = 0, binding = RENDER_BINDING_COAT_ALBEDO) readonly buffer CoatAlbedo { float coat_albedo[]; };
layout(std430, set = 0, binding = RENDER_BINDING_BELCOUR_TABLES) readonly buffer BelcourTables { float belcour_tables[]; };
layout(std430, set = 0, binding = RENDER_BINDING_ENV) readonly buffer Env { vec4 env[]; };   // RGB radiance per texel
// the marginal CDF over rows (env_h values, the last 1), then per row the conditional CDF over its columns
layout(std430, set = 0, binding = RENDER_BINDING_ENV_CDF) readonly buffer EnvCdf { float env_cdf[]; };

layout(push_constant) uniform PushBlock { RenderPush pc; };

layout(std430, set = 0, binding = RENDER_BINDING_LOBES) buffer Lobes { vec4 lobes[]; };   // the lobe pass's output

// The models' environment, as models.comp provides it. Belcour's and tm21's lobes: l changes from one evaluation to
// the next, so the lobe pass tabulates them over mu = cos theta_l at the nodes the symmetric variant's table uses,
// and every variant reads them from there (models/belcour18.glsl, BELCOUR_LOBES_OF_MU)
float model_coat_albedo(float mu) {
    float x = clamp(mu, 0.0f, 1.0f) * float(COAT_ALBEDO_NODES - 1u);
    uint i = min(uint(x), COAT_ALBEDO_NODES - 2u);
    return mix(coat_albedo[i], coat_albedo[i + 1], x - float(i));
}
uint model_layer_count() { return stack_layer_count(u_stack.info); }
LayerGpu model_layer(uint i) { return u_stack.layers[i]; }
bool model_use_tables() { return pc.use_tables != 0u; }
float model_table(uint i) { return belcour_tables[i]; }
uint model_convention() { return CONVENTION; }
float model_mu_jump() { return pc.mu_jump; }
#define BELCOUR_PRECOMPUTED_LOBES 1
#define BELCOUR_LOBES_OF_MU 1
vec4 model_lobe(uint k) { return lobes[k]; }
void model_lobe_store(uint k, vec4 x) { lobes[k] = x; }

#ifdef GONIO_USER_MODEL
#include "models/user_model.glsl"   // a model file compiled at run time (host/models/user_model.cpp)
#else
#include "models/all.glsl"
#endif

// ---- the environment: equirectangular, z up (render_interface.glsl) ---------------------------------------------
uint env_texel(vec3 w) {
    vec2 uv = env_uv(w);
    uint i = min(uint(uv.x * float(pc.env_w)), pc.env_w - 1u), j = min(uint(uv.y * float(pc.env_h)), pc.env_h - 1u);
    return j * pc.env_w + i;
}
float env_row_p(uint j) { return env_cdf[j] - (j > 0u ? env_cdf[j - 1u] : 0.0f); }
float env_col_p(uint j, uint i) {
    uint o = pc.env_h + j * pc.env_w;
    return env_cdf[o + i] - (i > 0u ? env_cdf[o + i - 1u] : 0.0f);
}
// first index k in [0, n) with cdf[o + k] > u (the CDF's last value is 1)
uint env_search(uint o, uint n, float u) {
    uint lo = 0u, hi = n - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1u;
        if (env_cdf[o + mid] > u) hi = mid; else lo = mid + 1u;
    }
    return lo;
}
// solid-angle density of the environment strategy: p(texel) W H / (2 pi^2 sin theta) (the map's uv square is
// 2 pi x pi in (phi, theta), and dw = sin(theta) dtheta dphi)
float env_pdf(vec3 w) {
    if (pc.env_sampled == 0u) return 0.0f;
    uint t = env_texel(w), j = t / pc.env_w, i = t - j * pc.env_w;
    float s = sqrt(max(1.0f - w.z * w.z, 0.0f));
    if (!(s > 1e-7f)) return 0.0f;
    return env_row_p(j) * env_col_p(j, i) * float(pc.env_w * pc.env_h) / (2.0f * PI * PI * s);
}
vec3 env_sample(vec2 u, OUT(float) pdf) {
    uint j = env_search(0u, pc.env_h, u.y);
    float c0 = j > 0u ? env_cdf[j - 1u] : 0.0f, pj = env_cdf[j] - c0;
    float fy = pj > 0.0f ? clamp((u.y - c0) / pj, 0.0f, 1.0f) : 0.5f;
    uint o = pc.env_h + j * pc.env_w;
    uint i = env_search(o, pc.env_w, u.x);
    float d0 = i > 0u ? env_cdf[o + i - 1u] : 0.0f, pi_ = env_cdf[o + i] - d0;
    float fx = pi_ > 0.0f ? clamp((u.x - d0) / pi_, 0.0f, 1.0f) : 0.5f;
    vec3 w = env_direction(vec2((float(i) + fx) / float(pc.env_w), (float(j) + fy) / float(pc.env_h)));
    pdf = env_pdf(w);
    return w;
}

// ---- the lobe strategy: GGX visible normals about v, reflected (one or two roughnesses, equal odds) ------------
float lobe_pdf_one(vec3 v, vec3 w, float alpha) {
    vec3 h = normalize(v + w);
    float vh = dot(v, h);
    if (!(vh > 0.0f)) return 0.0f;
    return ggx_visible_normal_pdf(v, h, alpha) / (4.0f * vh);
}
float lobe_pdf(vec3 v, vec3 w) {
    if (pc.alpha_lobe1 == pc.alpha_lobe0) return lobe_pdf_one(v, w, pc.alpha_lobe0);
    return 0.5f * (lobe_pdf_one(v, w, pc.alpha_lobe0) + lobe_pdf_one(v, w, pc.alpha_lobe1));
}

// the power heuristic's weight of strategy a among a, b, c (ratios: the lobe's density reaches 1e7 and more)
float power_weight(float a, float b, float c) {
    if (!(a > 0.0f)) return 0.0f;
    float rb = b / a, rc = c / a;
    return 1.0f / (1.0f + rb * rb + rc * rc);
}

void main() {
#ifndef GONIO_USER_MODEL
    if (pc.lobe_pass != 0u) {   // the model's lobes at the nodes of mu, before the pixels' dispatches
        uint node = gl_GlobalInvocationID.x;
        if (node < BELCOUR_MU_NODES) model_store_lobes(node, model_lobes_at(belcour_mu_node(node)));
        return;
    }
#endif
    uint pixel = gl_GlobalInvocationID.x;
    if (pixel >= pc.size * pc.size) return;
    uint py = pixel / pc.size, px = pixel - py * pc.size;
    vec3 n;
    if (!sphere_normal(px, py, pc.size, n)) return;
    // the local frame: z = n, x towards v = +z (the plane of incidence of the view, phi = 0), y = z cross x
    vec3 t1 = vec3(-n.x * n.z, -n.y * n.z, 1.0f - n.z * n.z);
    float tl = length(t1);
    t1 = tl > 1e-6f ? t1 / tl : vec3(1.0f, 0.0f, 0.0f);
    vec3 t2 = cross(n, t1);
    vec3 v = vec3(dot(vec3(0.0f, 0.0f, 1.0f), t1), 0.0f, n.z);
    CoatParams p = coat_params(u_stack.layers[0], u_stack.layers[1]);

    // per pixel and strategy: the lattice's shift (rng.glsl: stream = pixel, counter = strategy)
    Rng r = rng_init(pixel, 0u, pc.seed, 0x52454e44u);   // "REND"
    vec4 s01 = rng_next4(r), s2 = rng_next4(r);
    const vec2 R2 = vec2(0.7548776662466927f, 0.5698402909980532f);   // 1/g, 1/g^2, g^3 = g + 1 (Roberts 2018)
    vec3 sum = vec3(0.0f);
    for (uint k = pc.first_sample; k < pc.first_sample + pc.samples; ++k) {
        // k R2 mod 1 in float: k below 2^24, the fraction taken of each product
        vec2 lat = fract(vec2(float(k) * R2.x, float(k) * R2.y));
        vec2 ue = fract(lat + s01.xy), uc = fract(lat + s01.zw), ug = fract(lat + s2.xy);
        // environment
        float pe = 0.0f;
        vec3 w = pc.env_sampled != 0u ? env_sample(ue, pe) : n;
        vec3 wl = vec3(dot(w, t1), dot(w, t2), dot(w, n));
        if (pc.env_sampled != 0u && wl.z > 0.0f && pe > 0.0f) {
            vec3 f = eval_model(MODEL, p, TERM_TOP | TERM_BASE, wl, v);
            float pc_ = wl.z / PI, pg = lobe_pdf(v, wl);
            sum += f * env[env_texel(w)].rgb * (wl.z / pe * power_weight(pe, pc_, pg));
        }
        // cosine hemisphere
        wl = sample_cosine_hemisphere(uc.x, uc.y);
        if (wl.z > 0.0f) {
            w = wl.x * t1 + wl.y * t2 + wl.z * n;
            vec3 f = eval_model(MODEL, p, TERM_TOP | TERM_BASE, wl, v);
            float pc_ = wl.z / PI, pe2 = env_pdf(w), pg = lobe_pdf(v, wl);
            sum += f * env[env_texel(w)].rgb * (wl.z / pc_ * power_weight(pc_, pe2, pg));
        }
        // the GGX lobe about the mirror direction of v
        float alpha = s2.z < 0.5f ? pc.alpha_lobe0 : pc.alpha_lobe1;
        // the lobe's choice stratified too: alternate the two roughnesses along k
        if ((k & 1u) != 0u) alpha = s2.z < 0.5f ? pc.alpha_lobe1 : pc.alpha_lobe0;
        vec3 m = sample_ggx_visible_normal(v, alpha, ug.x, ug.y);
        wl = reflect_about(v, m);
        if (wl.z > 0.0f) {
            w = wl.x * t1 + wl.y * t2 + wl.z * n;
            float pg = lobe_pdf(v, wl);
            if (pg > 0.0f) {
                vec3 f = eval_model(MODEL, p, TERM_TOP | TERM_BASE, wl, v);
                float pc_ = wl.z / PI, pe2 = env_pdf(w);
                sum += f * env[env_texel(w)].rgb * (wl.z / pg * power_weight(pg, pc_, pe2));
            }
        }
    }
#if defined(GONIO_USER_MODEL) && defined(GONIO_MODEL_HINTS)
    // a user's delta lobes (model_lobes, roughness 0), which model_f leaves out: the light a delta sends to v comes
    // from one direction. The mirror direction of v is asked (a smooth interface's reflection); a delta it gives in
    // the direction v adds its weight times the light from there, pc.samples times (the host divides the sums by the
    // iterations). Deltas in other directions are not rendered (docs/RENDER.md).
    {
        vec3 lm = vec3(-v.x, -v.y, v.z);
        GonioLobe hl[GONIO_MAX_LOBES];   // an out parameter: only the first nh are read
        uint nh = model_lobes(lm, hl);
        vec3 w = lm.x * t1 + lm.y * t2 + lm.z * n;
        for (uint k = 0u; k < GONIO_MAX_LOBES; ++k) {
            if (k >= nh || hl[k].roughness != 0.0f || !(length(hl[k].direction) > 0.0f)) continue;
            if (dot(normalize(hl[k].direction), v) < 1.0f - 1e-6f) continue;
            sum += max(hl[k].weight, vec3(0.0f)) * env[env_texel(w)].rgb * float(pc.samples);
        }
    }
#endif
    accum[pixel] += vec4(sum, 0.0f);
}
