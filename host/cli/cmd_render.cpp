#include "cmd_render.h"
#include "common_options.h"
#include "render_case.h"
#include "text_format.h"
#include "vk_context.h"

#include <algorithm>

namespace gonio {

namespace {

constexpr const char* kRenderUsage = "STACK.toml --out DIR [options]";
constexpr const char* kRenderNotes =
    R"(render writes: reference.exr and MODEL.exr (RGBA float, A = the sphere), reference.png and MODEL.png
(the same exposure, x / (1 + x), sRGB), diff-MODEL.exr/png (MODEL - reference, red above, blue below),
reference-half-a.exr / -half-b.exr, render.json (per model: relative L1 and HDR-FLIP mean and 95th
percentile against the reference, beside the reference's own floor between its halves; times) and
figure.png (a grid of the spheres, six a row, then one of their FLIP maps; FLIP needs pip's flip-evaluator).
)";

// --theta-i of the table: sorted, in [0, 90), none twice
std::vector<double> table_angles(const std::string& opt, const std::string& v) {
    std::vector<double> t = parse_list(opt, v);
    std::sort(t.begin(), t.end());
    for (double a : t)
        if (!(a >= 0 && a < 90)) usage_error(opt + ": angles in [0, 90), got " + format_g9(a));
    if (std::adjacent_find(t.begin(), t.end()) != t.end()) usage_error(opt + ": an angle given twice");
    return t;
}

}   // namespace

OptionTable render_options(RenderSettings& a) {
    RenderRequest& r = a.r;
    const OptionTable models = model_options(a.m);
    return OptionTable{
               {"--out", "DIR", "where the images and render.json go (required)",
                [&r](const std::string& v) { r.out = v; }},
               {"--env", "NAME|FILE.exr",
                "the light: furnace (uniform radiance 1), studio (three disc lights over a dim gradient, procedural), "
                "one of Debian blender-data's maps city, courtyard, forest, interior, night, sunrise, sunset (and its "
                "studio as a file: /usr/share/blender/datafiles/studiolights/world/studio.exr), or an EXR file; "
                "equirectangular, z up, row 0 the zenith; negative texels set to 0 and counted (default studio)",
                [&r](const std::string& v) { r.env = v; }},
               {"--size", "N",
                "pixels per side, 8 to 2048; an orthographic camera along -z, the unit sphere filling the frame "
                "(default 256)",
                [&r](const std::string& v) {
                    const uint64_t n = parse_count("--size", v);
                    if (n < 8 || n > 2048) usage_error("--size must be 8 to 2048 pixels, got " + std::to_string(n));
                    r.size = uint32_t(n);
                }},
               {"--reference", "DIR",
                "the reference's table: a render output (DIR/table-a, DIR/table-b: two independent halves) or a "
                "simulate output over incident angles (DIR/state.gonio; its floor from f +- se); without it render "
                "simulates two halves of --paths per angle at --theta-i and keeps them in OUT/table-{a,b}",
                [&r](const std::string& v) { r.reference = v; }},
               {"--paths", "N", "paths per incident angle of the table, both halves, at least 2 (default 2e6)",
                [&r](const std::string& v) {
                    r.paths = parse_count("--paths", v);
                    if (r.paths < 2) usage_error("--paths: at least 2 per angle (two halves)");
                }},
               {"--theta-i", "LIST", "the table's incident angles, in [0, 90) (A:B:S ranges) (default 0:88:2)",
                [&r](const std::string& v) { r.theta_i = table_angles("--theta-i", v); }},
               {"--spp", "N",
                "the models' iterations per pixel, 1 to 2^24, each one sample of the environment, the cosine "
                "hemisphere and the GGX lobe, combined by MIS (default 64)",
                [&r](const std::string& v) {
                    const uint64_t n = parse_count("--spp", v);
                    if (n < 1 || n > (1u << 24)) usage_error("--spp must be 1 to 2^24");
                    r.spp = uint32_t(n);
                }},
               seed_option(r.seed, "seed of the table and of the models' samples (same seed, same bytes) (default 1)"),
               retold(models, "--models", "render only these models (gonio models, or the ids of --model files)"),
               retold(models, "--model",
                      "also render your own model, one GLSL file as compare takes it (repeatable; render.comp is "
                      "compiled with it before anything is simulated)"),
               {"--spectral", nullptr,
                "the reference's table traced band by band (simulate --spectral), its bins' linear sRGB under D65; the "
                "stack's RGB run rendered beside it and their colour difference per pixel (CIEDE2000, Delta E_ITP); the "
                "models evaluated in RGB on the stack reduced by --reduction (docs/RENDER.md)",
                [&r](const std::string&) { r.spectral = true; }},
               {"--reduction", "R",
                "with --spectral: how the RGB run and the models take a measured material's n and k: dominant (at the "
                "sRGB primaries' dominant wavelengths, the default) or f0 (the spectral F0's colour matched)",
                [&r](const std::string& v) {
                    try {
                        r.reduction = parse_rgb_reduction(v);
                        r.reduction_given = true;
                    } catch (const std::invalid_argument& e) { usage_error(std::string("--reduction: ") + e.what()); }
                }},
               {"--no-report", nullptr, "no FLIP and no figure (tools/render_report.py)",
                [&r](const std::string&) { r.no_report = true; }},
               device_option(r.ctx),
               {"--quiet", nullptr, "no progress lines", [&r](const std::string&) { r.quiet = true; }},
           } +
           spectral_band_options(r.bands, r.bands_given, "--spectral");
}

void check_render_settings(RenderSettings& settings) {
    RenderRequest& a = settings.r;
    if ((a.bands_given || a.reduction_given) && !a.spectral)
        usage_error("--bands, --band-points, --band-paths and --reduction go with --spectral");
    if (a.spectral && !a.reference.empty())
        usage_error("--spectral traces its table now: --reference is not taken with it");
    // --model files: read and compiled before anything is simulated (a broken file: FILE:LINE, exit 2)
    load_model_files(settings.m, false);
    a.models = settings.m.models;
}

namespace {

int run_render(RenderSettings& settings, const std::vector<std::string>& operands) {
    RenderRequest& a = settings.r;
    if (operands.size() > 1) usage_error("render takes one stack file: gonio render " + std::string(kRenderUsage));
    if (operands.empty() || a.out.empty())
        usage_error("render needs a stack file and --out DIR: gonio render " + std::string(kRenderUsage));
    a.stack = operands[0];
    check_render_settings(settings);
    const Stack s = parse_stack_file(a.stack);
    VkContext ctx(a.ctx);
    return render_to_directory(ctx, s, a);   // the environment is read first, before the table is traced
}

}   // namespace

Command render_command() {
    return {"render", kRenderUsage,
            "the reference and every model that can represent the stack on a sphere under an environment map; their "
            "differences and HDR-FLIP (docs/RENDER.md)",
            kRenderNotes, invocation(&render_options, &run_render)};
}

}   // namespace gonio
