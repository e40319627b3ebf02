#include "cmd_simulate.h"
#include "cmd_render.h"
#include "compare.h"
#include "args.h"
#include "histogram.h"
#include "json.h"
#include "models.h"
#include "user_model.h"
#include "output.h"
#include "python_tool.h"
#include "reference.h"
#include "stack.h"
#include "state.h"
#include "validation.h"
#include "vk_context.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace gonio {

namespace {

// Figures and report.html of a compare run, by tools/report.py.
void make_report(const std::string& out) { run_python_tool("report.py", out, "the figures and report.html"); }

// compare --render ENV: gonio render into OUT/render with compare's models and seed, its own table (0:88:2,
// --render-paths per angle); report.html shows its figure and numbers.
int render_for_compare(VkContext& ctx, const Stack& s, const Environment& env, const Args& a,
                       const ModelOptions& models, const std::string& out) {
    RenderRequest r;
    r.stack = a.positional[0];
    r.env = a.render_env;
    r.out = out + "/render";
    r.size = a.render_size ? a.render_size : 128;
    r.paths = a.render_paths;
    r.seed = a.sim.seed;
    r.models = models;   // with the --model files (compiled into render.comp when the render starts)
    r.quiet = !a.sim.progress;
    r.no_report = a.no_report;
    if (a.sim.progress) std::fprintf(stderr, "gonio: --render %s into %s\n", r.env.c_str(), r.out.c_str());
    return render_to_directory(ctx, s, env, r);
}

}   // namespace

int cmd_simulate(const Args& a, bool compare) {
    if (a.positional.size() != 1) usage_error(std::string(compare ? "compare" : "simulate") + " takes one stack file");
    Stack s = parse_stack_file(a.positional[0]);
    Args args = a;
    // --model files are read and compiled before any simulation: a broken file is refused at once (FILE:LINE)
    for (const std::string& f : a.model_files) {
        args.models.user_models.push_back(load_user_model(f));
        if (a.sim.progress)
            std::fprintf(stderr, "gonio: model %s (%s) compiled in %.2f s\n",
                         args.models.user_models.back()->header.id.c_str(), f.c_str(),
                         args.models.user_models.back()->compile_seconds);
    }
    if (!a.model_files.empty()) check_model_ids(args.models);
    // --render ENV: the environment is read before any simulation (an unknown name or a broken file is refused now)
    std::optional<Environment> render_env;
    if (!a.render_env.empty()) render_env = load_render_environment(a.render_env);
    if (args.sim.rse_target > 0 && !args.paths_given) args.sim.paths = 10000000000ull;
    validate_options(args.sim);
    std::string out = a.out.empty() ? (a.resume.empty() ? "out/" + safe_file_name(s.name) : a.resume) : a.out;
    std::optional<SimResult> previous;
    if (!a.resume.empty()) {
        if (a.cpu_twin) usage_error("--resume works with the device walk only");
        previous = load_state(a.resume + "/state.gonio");
        check_resumable(*previous, s, args.sim);
    }
    fs::create_directories(out);
    if (a.checkpoint_seconds > 0) {   // a killed run leaves at most this much work undone (--resume DIR continues it)
        args.sim.checkpoint_seconds = a.checkpoint_seconds;
        args.sim.on_checkpoint = [out](const SimResult& partial) { save_state(out + "/state.gonio", partial); };
    }
    SimResult r;
    int rc = 0;
    std::vector<ModelSlices> models;
    Json models_summary;
    if (a.cpu_twin) {
        if (compare) usage_error("compare runs on the device (--cpu-twin is for simulate)");
        r = simulate_cpu(s, args.sim, std::max(1u, std::thread::hardware_concurrency()));
    } else {
        VkContext ctx(a.ctx);
        if (a.sim.progress) std::fprintf(stderr, "gonio: device %s\n", ctx.device_info().name.c_str());
        r = simulate_gpu(ctx, s, args.sim, previous ? &*previous : nullptr);
        if (compare) {
            std::vector<ModelCost> costs;
            ModelStageCost stage;
            models = evaluate_models(ctx, s, model_grid(r), &costs, args.models, &stage);
            models_summary = models_json(r, models, costs, &stage);
            warn_energy_gains(r, models);
            if (render_env) rc = std::max(rc, render_for_compare(ctx, s, *render_env, a, args.models, out));
        }
        rc = check_validation(ctx);
    }
    write_exr(out + "/" + safe_file_name(s.name) + ".exr", r, compare ? &models : nullptr);
    write_slices_csv(out + "/slices.csv", r, compare ? &models : nullptr);
    write_summary_json(out + "/summary.json", r, compare ? &models_summary : nullptr);
    save_state(out + "/state.gonio", r);
    for (size_t i = 0; i < r.angles.size(); ++i) {
        EnergyBook e = energy_book(r, i);
        if (e.invalid.x > 0) {   // walk.glsl path_is_finite: booked apart, never as absorbed or leaving
            std::fprintf(stderr,
                         "gonio: theta_i %g: %.0f paths booked a number that is not finite (summary.json: energy "
                         "invalid %.3g): a bug, please report it with the stack file and the command\n",
                         r.angles[i].theta_i_deg, e.invalid.x * double(r.angles[i].paths), e.invalid.x);
            rc = 1;
        }
        std::printf("theta_i %5g: R %.5f %.5f %.5f  T %.5f %.5f %.5f  %llu paths (%s), median rse %.4f, worst %.4f\n",
                    r.angles[i].theta_i_deg, e.reflected.x, e.reflected.y, e.reflected.z, e.transmitted.x,
                    e.transmitted.y, e.transmitted.z, (unsigned long long)r.angles[i].paths,
                    r.angles[i].stopped_by.c_str(), r.angles[i].median_rse, r.angles[i].worst_rse);
    }
    print_model_metrics(r, models);
    for (const ModelSlices& m : models)
        if (!m.invalid.empty()) {   // never scored: summary.json says where
            std::fprintf(stderr, "gonio: %s: its bins cannot be used: %s\n", m.id.c_str(), m.invalid.c_str());
            rc = 1;
        }
    std::printf("wrote %s/{%s.exr,slices.csv,summary.json,state.gonio}\n", out.c_str(), safe_file_name(s.name).c_str());
    if (non_finite_json_numbers() > 0) {
        std::fprintf(stderr,
                     "gonio: %llu numbers of summary.json were not finite (written as null): a bug, please report it\n",
                     (unsigned long long)non_finite_json_numbers());
        rc = 1;
    }
    if (compare && !a.no_report) make_report(out);
    return rc;
}

}   // namespace gonio
