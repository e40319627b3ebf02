#include "cmd_compare.h"
#include "cmd_render.h"
#include "common_options.h"
#include "model_evaluator.h"
#include "models_json.h"
#include "python_tool.h"
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
};

OptionTable compare_options(CompareSettings& a) {
    const OptionTable report = {
        {"--no-report", nullptr, "no figures, no report.html", [&a](const std::string&) { a.no_report = true; }}};
    return walk_options(a.walk) + report + model_options(a.models) + render_along_options(a.render);
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
    if (a.walk.sim.progress) std::fprintf(stderr, "gonio: --render %s into %s\n", r.env.c_str(), r.out.c_str());
    return render_to_directory(ctx, s, env, r);
}

// What compare computes on the device: the reference, the models on its bins, their metrics; the render.
struct CompareResult {
    SimResult r;
    std::vector<ModelSlices> models;
    Json models_summary;
    int rc = 0;   // the render's and the validation layer's
};

CompareResult compare_on_device(const CompareSettings& a, const SimulateRun& run, const std::string& stack_file,
                                const std::optional<Environment>& env) {
    CompareResult c;
    VkContext ctx(a.walk.ctx);
    if (run.sim.progress) std::fprintf(stderr, "gonio: device %s\n", ctx.device_info().name.c_str());
    c.r = simulate_gpu(ctx, run.stack, run.sim, run.resumed());
    std::vector<ModelCost> costs;
    ModelStageCost stage;
    c.models = evaluate_models(ctx, run.stack, model_grid(c.r), &costs, a.models.models, &stage);
    c.models_summary = models_json(c.r, c.models, costs, &stage);
    warn_energy_gains(c.r, c.models);
    if (env) c.rc = render_for_compare(ctx, run.stack, *env, a, stack_file, run.out);
    c.rc = std::max(c.rc, check_validation(ctx));
    return c;
}

int run_compare(CompareSettings& a, const std::vector<std::string>& operands) {
    check_render_along(a.render);
    Stack s = stack_operand("compare", operands);
    // --model files are read and compiled before any simulation: a broken file is refused at once (FILE:LINE)
    load_model_files(a.models, a.walk.sim.progress);
    // --render ENV: the environment is read before any simulation (an unknown name or a broken file is refused now)
    std::optional<Environment> env;
    if (!a.render.env.empty()) env = load_render_environment(a.render.env);
    const SimulateRun run = prepare_run(a.walk, std::move(s));
    const CompareResult c = compare_on_device(a, run, operands[0], env);
    const int rc = std::max(c.rc, write_run(run, c.r, &c.models, &c.models_summary));
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
