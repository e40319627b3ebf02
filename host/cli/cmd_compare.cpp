#include "cmd_compare.h"
#include "common_options.h"
#include "python_tool.h"
#include "render_case.h"
#include "rgb_vs_spectral.h"
#include "spectral_compare.h"
#include "simulate_run.h"
#include "validation.h"
#include "vk_context.h"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace gonio {

namespace {

constexpr const char* kCompareNotes =
    R"(compare writes everything simulate writes, plus: model rows in slices.csv (source = model id, reflection
side, se 0), and in summary.json per model and incident angle: RMSE and mean absolute error in the seed's
remapped space log(1 + sqrt f), RMSE and mean relative error in f, directional albedo (model, reference,
error), the largest remapped error and its bin, the reference's own noise on the same bins (remapped), and
whether the model is within that noise, and whether its albedo (reflected + transmitted) breaks the white-furnace
bound (reflects_more_than_it_receives: flagged and warned on stderr, never clamped). A model that cannot represent
the stack is listed with the reason.
It then draws, with tools/report.py (Python 3 + matplotlib): slices.png (the seed's in-plane slice diagrams,
log(1 + sqrt f) of luminance), albedo.png, topview-<i>.png (top view of the hemisphere: reference, models,
signed differences), and report.html with the metric tables. --no-report skips them.
)";

struct CompareSettings {
    WalkSettings walk;
    ModelSettings models;
    RenderAlong render;
    bool no_report = false;
    bool spectral = false, rgb_vs_spectral = false, bands_given = false, reduction_given = false;
    SpectralBands bands;
    RgbReduction reduction = RgbReduction::Dominant;
};

OptionTable compare_options(CompareSettings& a) {
    const OptionTable report = {
        {"--no-report", nullptr, "no figures, no report.html", [&a](const std::string&) { a.no_report = true; }}};
    const OptionTable colour = {
        {"--spectral", nullptr,
         "the reference traced band by band (simulate --spectral) and every model evaluated band by band on its bins; "
         "each model's colour difference per bin and angle, CIEDE2000 and Delta E_ITP (docs/SPECTRAL.md)",
         [&a](const std::string&) { a.spectral = true; }},
        {"--rgb-vs-spectral", nullptr,
         "instead of the models: the stack traced spectrally (simulate --spectral) and in RGB (its measured materials "
         "reduced by --reduction), and their colour difference per bin and angle, CIEDE2000 and Delta E_ITP "
         "(docs/SPECTRAL.md)",
         [&a](const std::string&) { a.rgb_vs_spectral = true; }},
        {"--reduction", "R",
         "with --rgb-vs-spectral (the RGB run) or --spectral (the production models, evaluated in RGB): how a measured "
         "conductor's n and k are taken to three channels: dominant (at the sRGB primaries' dominant wavelengths, as "
         "every RGB run; the default) or f0 (the spectral F0's colour matched)",
         [&a](const std::string& v) {
             try {
                 a.reduction = parse_rgb_reduction(v);
                 a.reduction_given = true;
             } catch (const std::invalid_argument& e) { usage_error(std::string("--reduction: ") + e.what()); }
         }}};
    return walk_options(a.walk) + report + model_options(a.models) + render_along_options(a.render) + colour +
           spectral_band_options(a.bands, a.bands_given, "--spectral or --rgb-vs-spectral");
}

// compare --render ENV: gonio render into OUT/render with compare's models and seed, its own table (0:88:2,
// --render-paths per angle); report.html shows its figure and numbers.
int render_for_compare(VkContext& ctx, const Stack& s, const Environment& env, const CompareSettings& a,
                       const std::string& stack_file, const std::string& out) {
    RenderRequest r;
    r.stack = stack_file;
    r.env = a.render.env;
    r.out = out + "/render";
    r.size = a.render.size ? a.render.size : 128;
    r.paths = a.render.paths;
    r.seed = a.walk.sim.seed;
    r.models = a.models.models;   // with the --model files (compiled into render.comp when the render starts)
    r.quiet = !a.walk.sim.progress;
    r.no_report = a.no_report;
    r.spectral = a.spectral;   // compare --spectral --render: render --spectral (the RGB run beside it)
    r.bands = a.bands;
    r.reduction = a.reduction;
    if (a.walk.sim.progress) std::fprintf(stderr, "gonio: --render %s into %s\n", r.env.c_str(), r.out.c_str());
    return render_to_directory(ctx, s, r, &env);
}

// What compare computes on the device: the case with its models and its files, then the render; the status of the
// files, the render and the validation layer.
int compare_on_device(const CompareSettings& a, const Case& run, const std::string& stack_file,
                      const std::optional<Environment>& env) {
    VkContext ctx(a.walk.ctx);
    if (run.sim.progress) std::fprintf(stderr, "gonio: device %s\n", ctx.device_info().name.c_str());
    int rc = run_and_write_case(ctx, run, &a.models.models);
    if (env) rc = std::max(rc, render_for_compare(ctx, run.stack, *env, a, stack_file, run.out));
    return std::max(rc, check_validation(ctx));
}

// compare --rgb-vs-spectral: no models, no render; the two runs and their colour difference.
int run_colour_comparison(const CompareSettings& a, Stack s) {
    if (!a.models.files.empty() || !a.models.models.selected.empty())
        usage_error(
            "--rgb-vs-spectral compares the stack's RGB run with its spectral run: it evaluates no models "
            "(--model, --models)");
    if (!a.render.env.empty()) usage_error("--rgb-vs-spectral does not render (--render)");
    const Case run = prepare_run(a.walk, std::move(s));
    VkContext ctx(a.walk.ctx);
    const int rc = run_rgb_vs_spectral(run, a.bands, a.reduction, ctx);
    return std::max(rc, check_validation(ctx));
}

// compare --spectral: the spectral reference and the models band by band; with --render ENV, render --spectral into
// OUT/render.
int run_spectral_models(CompareSettings& a, Stack s, const std::string& stack_file) {
    load_model_files(a.models, a.walk.sim.progress);
    std::optional<Environment> env;
    if (!a.render.env.empty()) env = load_render_environment(a.render.env);
    const Case run = prepare_run(a.walk, std::move(s));
    VkContext ctx(a.walk.ctx);
    int rc = run_spectral_compare(run, a.bands, a.models.models, a.reduction, ctx);
    if (env) rc = std::max(rc, render_for_compare(ctx, run.stack, *env, a, stack_file, run.out));
    return std::max(rc, check_validation(ctx));
}

int run_compare(CompareSettings& a, const std::vector<std::string>& operands) {
    check_render_along(a.render);
    if (a.spectral && a.rgb_vs_spectral) usage_error("give --spectral or --rgb-vs-spectral, not both");
    if (a.reduction_given && !a.rgb_vs_spectral && !a.spectral)
        usage_error("--reduction goes with --spectral or --rgb-vs-spectral");
    if (a.bands_given && !a.rgb_vs_spectral && !a.spectral)
        usage_error("--bands and --band-paths go with --spectral or --rgb-vs-spectral");
    Stack s = stack_operand("compare", operands);
    if ((a.spectral || a.rgb_vs_spectral) && a.walk.sim.phi_i_deg != 0.0)
        usage_error(std::string(a.spectral ? "--spectral" : "--rgb-vs-spectral") +
                    " traces the plane of incidence (phi_i 0); --phi-i goes with the RGB walk");
    if (a.rgb_vs_spectral) return run_colour_comparison(a, std::move(s));
    if (a.spectral) return run_spectral_models(a, std::move(s), operands[0]);
    // --model files are read and compiled before any simulation: a broken file is refused at once (FILE:LINE)
    load_model_files(a.models, a.walk.sim.progress);
    // --render ENV: the environment is read before any simulation (an unknown name or a broken file is refused now)
    std::optional<Environment> env;
    if (!a.render.env.empty()) env = load_render_environment(a.render.env);
    const Case run = prepare_run(a.walk, std::move(s));
    const int rc = compare_on_device(a, run, operands[0], env);
    if (!a.no_report) run_python_tool("report.py", run.out, "the figures and report.html");
    return rc;
}

}   // namespace

Command compare_command() {
    return {"compare", "STACK.toml [options]",
            "simulate, then evaluate every analytic model that can represent the stack on the same bins, and write "
            "how far each is from the reference",
            kCompareNotes, invocation(&compare_options, &run_compare)};
}

}   // namespace gonio
