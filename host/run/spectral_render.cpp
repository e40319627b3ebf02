// spectral_render.cpp: see spectral_render.h.
#include "spectral_render.h"
#include "image.h"
#include "output.h"
#include "spectral_simulate.h"
#include "spectral_sphere.h"
#include "stack_spectral.h"
#include "state.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

namespace gonio {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}   // namespace

SpectralRenderTables spectral_render_tables(VkContext& ctx, const Stack& s, const RenderRequest& a) {
    const SimOptions o = table_half_options(a);
    SpectralRenderTables t;
    auto start = std::chrono::steady_clock::now();
    SpectralResult half[2];
    int rc = 0;
    for (int h = 0; h < 2; ++h) {
        Case run{s, o, a.out, std::nullopt};
        run.sim.seed = a.seed + uint32_t(h) * 0x9e3779b9u;
        half[h] = trace_spectral(run, a.bands, &ctx, 1, rc);
        const std::string dir = a.out + (h ? "/spectral-b" : "/spectral-a");
        fs::create_directories(dir);
        write_spectral_exr(dir + "/" + safe_file_name(s.name) + ".exr", half[h]);
        write_spectral_summary(dir + "/summary.json", half[h]);
    }
    if (rc != 0) throw std::runtime_error("render --spectral: a path's weight stopped being finite in the table");
    t.spectral = table_from_spectral_halves(half[0], half[1]);
    t.spectral_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    t.rgb_stack = stack_reduced_to_rgb(s, a.reduction, t.clipped);
    if (!a.quiet) std::fprintf(stderr, "render: the RGB run (reduction %s)\n", to_string(a.reduction));
    const std::array<SimResult, 2> rgb = simulate_table_halves(ctx, t.rgb_stack, o);
    for (int h = 0; h < 2; ++h) {
        const std::string dir = a.out + (h ? "/rgb-table-b" : "/rgb-table-a");
        fs::create_directories(dir);
        save_state(dir + "/state.gonio", rgb[size_t(h)]);
    }
    t.rgb = table_from_halves(rgb[0], rgb[1]);
    t.rgb_seconds = seconds_since(start);
    if (!t.clipped.empty())
        std::fprintf(stderr, "render: warning: the %s reduction: %s\n", to_string(a.reduction), t.clipped.c_str());
    return t;
}

Json rgb_vs_spectral_on_sphere(const SpectralRenderTables& t, const ReferenceRender& spectral, const Environment& env,
                               const RenderRequest& a, const std::vector<std::pair<std::string, std::string>>& attrs,
                               double exposure) {
    const auto start = std::chrono::steady_clock::now();
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    const ReferenceRender rgb = render_reference(t.rgb, env, a.size, threads);
    const ReferenceRender white = render_reference(white_diffuser_table(t.spectral), env, a.size, threads);
    const SphereColourError e = sphere_colour_error(spectral, rgb, white.image);
    write_rgba_exr(a.out + "/reference-rgb.exr", rgb.image, attrs);
    write_tonemapped_png(a.out + "/reference-rgb.png", rgb.image, exposure);
    write_rgba_exr(a.out + "/rgb-vs-spectral-de2000.exr", e.de2000, attrs);
    write_rgba_exr(a.out + "/rgb-vs-spectral-de-itp.exr", e.de_itp, attrs);
    write_rgba_exr(a.out + "/rgb-vs-spectral-noise.exr", e.noise, attrs);
    write_difference_png(a.out + "/rgb-vs-spectral-de2000.png", e.de2000, 10.0);
    Json j;
    j["what"] =
        "the stack's RGB run (its measured materials reduced to three channels) against its spectral run, each "
        "rendered from its table; per pixel the colour over a white diffuser's luminance there (its reflectance "
        "factor), CIEDE2000 and Delta E_ITP, over the pixels on the sphere whose spectral Y reaches 1% of the white's";
    j["reduction"] = to_string(a.reduction);
    if (!t.clipped.empty()) j["reduction_clipped"] = t.clipped;
    j["bands"] = {{"width_nm", json_number(a.bands.width_nm)},
                  {"count", a.bands.count()},
                  {"points", a.bands.points},
                  {"paths", to_string(a.bands.pass_paths)}};
    j["table_seconds"] = {{"spectral", json_number(t.spectral_seconds)}, {"rgb", json_number(t.rgb_seconds)}};
    j["lit_pixels"] = e.lit;
    j["de2000"] = {{"median", json_number(e.median_de2000)},
                   {"p95", json_number(e.p95_de2000)},
                   {"max", json_number(e.max_de2000)}};
    j["de_itp"] = {{"median", json_number(e.median_de_itp)},
                   {"p95", json_number(e.p95_de_itp)},
                   {"max", json_number(e.max_de_itp)}};
    j["noise_de2000_median"] = json_number(e.median_noise);
    j["noise"] = "per pixel sqrt(dE_s^2 + dE_r^2) / 2, dE the CIEDE2000 between a render's two halves";
    j["seconds"] = json_number(seconds_since(start));
    if (!a.quiet)
        std::fprintf(stderr,
                     "render: RGB (%s) against spectral on %zu lit pixels: CIEDE2000 median %.2f, p95 %.2f, max %.2f;"
                     " dE_ITP median %.1f; noise %.2f\n",
                     to_string(a.reduction), e.lit, e.median_de2000, e.p95_de2000, e.max_de2000, e.median_de_itp,
                     e.median_noise);
    return j;
}

}   // namespace gonio
