#version 450
// render_samples.comp: gonio render's samples of the environment, drawn once per pixel and iteration for every model
// (docs/RENDER.md). An orthographic camera looks down -z at a unit sphere filling the frame: at pixel centre (x, y)
// the normal is n = (x, y, sqrt(1 - x^2 - y^2)) and the view direction is v = +z. The sphere is convex and the
// environment distant, so a pixel is exactly the integral over the upper hemisphere of the local frame of
//     L(w) f(w, v) cos(theta_w) dw      (f(l, v): l the light's direction, v the viewer's; cosine excluded)
// estimated with three strategies, one sample of each per iteration, combined by the power heuristic (Veach 1997,
// section 9.2.4): the environment (a CDF over texels of max(luminance - mean, 0) x sin(theta): MIS compensation,
// Karlik et al. 2019; none for a constant map), the cosine hemisphere, and a GGX lobe about the mirror direction of v
// (visible normals, at the top interface's roughness and, over a conductor base, half the time at the base's), which
// finds the smooth interfaces that the models evaluate as GGX at 1e-4. None of their densities depends on the model:
// each sample is stored with its weight L(w) cos(theta_w) / pdf x its MIS weight, and each model's pass
// (render.comp) sums f(w, v) x weight. The sample points are a rank-1 lattice (R2, Roberts 2018) shifted per pixel
// and strategy by rng.glsl's counter-based numbers: deterministic for a seed, on any dispatch shape and tiling.
// The lavapipe loop limiter (65535 loop trips per invocation): a dispatch runs pc.samples iterations, each two binary
// searches (host/render/model_render.cpp keeps the product far below).
#extension GL_GOOGLE_include_directive : require

#include "compat.glsl"
#include "ggx.glsl"
#include "interface.glsl"
#include "rng.glsl"
#include "render_interface.glsl"

layout(local_size_x = RENDER_GROUP_SIZE) in;

layout(std430, set = 0, binding = RENDER_BINDING_ENV) readonly buffer Env { vec4 env[]; };   // RGB radiance per texel
// the marginal CDF over rows (env_h values, the last 1), then per row the conditional CDF over its columns
layout(std430, set = 0, binding = RENDER_BINDING_ENV_CDF) readonly buffer EnvCdf { float env_cdf[]; };
layout(std430, set = 0, binding = RENDER_BINDING_SAMPLES) writeonly buffer Samples { vec4 samples[]; };

layout(push_constant) uniform PushBlock { RenderPush pc; };

// ---- the environment: equirectangular, z up (render_interface.glsl) ---------------------------------------------
uint env_texel(vec3 w) { return env_texel_index(w, pc.env_w, pc.env_h); }
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

void store_sample(uint k, uint s, uint local, vec3 wl, vec3 weight) {
    uint i = render_sample_index(k, s, local, pc.batch_first, pc.tile_pixels);
    samples[2u * i] = vec4(wl, 0.0f);
    samples[2u * i + 1u] = vec4(weight, 0.0f);
}

void main() {
    uint local = gl_GlobalInvocationID.x;
    uint pixel = pc.pixel_first + local;
    if (local >= pc.tile_pixels || pixel >= pc.size * pc.size) return;
    uint py = pixel / pc.size, px = pixel - py * pc.size;
    vec3 n;
    if (!sphere_normal(px, py, pc.size, n)) return;   // off the sphere: no samples (the models' pass skips it too)
    vec3 t1, t2, v;
    sphere_frame(n, t1, t2, v);

    // per pixel and strategy: the lattice's shift (rng.glsl: stream = pixel, counter = strategy)
    Rng r = rng_init(pixel, 0u, pc.seed, 0x52454e44u);   // "REND"
    vec4 s01 = rng_next4(r), s2 = rng_next4(r);
    const vec2 R2 = vec2(0.7548776662466927f, 0.5698402909980532f);   // 1/g, 1/g^2, g^3 = g + 1 (Roberts 2018)
    for (uint k = pc.first_sample; k < pc.first_sample + pc.samples; ++k) {
        // k R2 mod 1 in float: k below 2^24, the fraction taken of each product
        vec2 lat = fract(vec2(float(k) * R2.x, float(k) * R2.y));
        vec2 ue = fract(lat + s01.xy), uc = fract(lat + s01.zw), ug = fract(lat + s2.xy);
        // environment
        float pe = 0.0f;
        vec3 w = pc.env_sampled != 0u ? env_sample(ue, pe) : n;
        vec3 wl = vec3(dot(w, t1), dot(w, t2), dot(w, n));
        vec3 weight = vec3(0.0f);
        if (pc.env_sampled != 0u && wl.z > 0.0f && pe > 0.0f) {
            float pc_ = wl.z / PI, pg = lobe_pdf(v, wl);
            weight = env[env_texel(w)].rgb * (wl.z / pe * power_weight(pe, pc_, pg));
        }
        store_sample(k, 0u, local, wl, weight);
        // cosine hemisphere
        wl = sample_cosine_hemisphere(uc.x, uc.y);
        weight = vec3(0.0f);
        if (wl.z > 0.0f) {
            w = wl.x * t1 + wl.y * t2 + wl.z * n;
            float pc_ = wl.z / PI, pe2 = env_pdf(w), pg = lobe_pdf(v, wl);
            weight = env[env_texel(w)].rgb * (wl.z / pc_ * power_weight(pc_, pe2, pg));
        }
        store_sample(k, 1u, local, wl, weight);
        // the GGX lobe about the mirror direction of v
        float alpha = s2.z < 0.5f ? pc.alpha_lobe0 : pc.alpha_lobe1;
        // the lobe's choice stratified too: alternate the two roughnesses along k
        if ((k & 1u) != 0u) alpha = s2.z < 0.5f ? pc.alpha_lobe1 : pc.alpha_lobe0;
        vec3 m = sample_ggx_visible_normal(v, alpha, ug.x, ug.y);
        wl = reflect_about(v, m);
        weight = vec3(0.0f);
        if (wl.z > 0.0f) {
            w = wl.x * t1 + wl.y * t2 + wl.z * n;
            float pg = lobe_pdf(v, wl);
            if (pg > 0.0f) {
                float pc_ = wl.z / PI, pe2 = env_pdf(w);
                weight = env[env_texel(w)].rgb * (wl.z / pg * power_weight(pg, pc_, pe2));
            }
        }
        store_sample(k, 2u, local, wl, weight);
    }
}
