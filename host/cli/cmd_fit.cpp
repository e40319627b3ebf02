#include "cmd_fit.h"
#include "input_file.h"

#include "common_options.h"
#include "fit_json.h"
#include "json.h"
#include "model_fit.h"
#include "models.h"
#include "python_tool.h"
#include "simulate_run.h"
#include "state.h"
#include "text_format.h"
#include "user_model.h"
#include "validation.h"
#include "vk_context.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

namespace gonio {

namespace {

const char* kFitNotes =
    R"(fit simulates the reference as simulate does (its options; --out DIR gets simulate's files), then changes the
free keys of the stack the model sees until the model's bins, recomputed exactly as compare computes them at every
step, are closest to the reference's over every incident angle (Levenberg-Marquardt, forward-difference Jacobian).
A free key is layer.N.KEY (N from 1, top to bottom; a key of that layer's kind, as in a stack file; an RGB key is
fitted as one value in every channel, or one channel alone as layer.N.KEY.r, .g or .b) or exterior_ior. --loss log (default): the mean square of
log(1 + sqrt f_model) - log(1 + sqrt f_reference) over bins and channels, compare's RMSE squared; --loss cosine: the
mean of (f_model - f_reference)^2 times each cell's projected solid angle, the cosine-weighted L2; --loss chi2: the
mean square of (model - reference) / se over the bins with paths. Each parameter's standard error is the
reference's noise (its bins' standard errors) through the linearised fit; a parameter the loss does not move with is
reported as unconstrained, one at the end of its range as at its limit. Writes DIR/fit.json: "parameters" (value, se,
start, constrained, at_limit, and for an RGB key its channels: rgb, r, g or b), "correlation", "loss" (start, best), "angles" (per incident angle, the model at the
start and at the fit: RMSE, chi2/dof, mean z, within the reference's noise), and how the iterations ended; slices.csv,
summary.json and the EXR hold the reference, the model at the start (its id) and at the fit (ID@fit), as compare
writes models, and report.html shows them (unless --no-report). With --reference DIR the reference is an earlier
run's (DIR/state.gonio), not simulated again, and the files go to --out.
)";

struct FitSettings {
    WalkSettings walk;
    std::string reference;   // --reference DIR: an earlier run's state instead of a simulation
    bool no_report = false;
    FitSpec spec;   // --model, --free, --start, --loss
};

std::vector<std::string> split_commas(const std::string& v) {
    std::vector<std::string> out;
    size_t a = 0;
    while (a <= v.size()) {
        const size_t b = std::min(v.find(',', a), v.size());
        if (b > a) out.push_back(v.substr(a, b - a));
        a = b + 1;
    }
    return out;
}

}   // namespace

OptionTable fit_spec_options(FitSpec& spec) {
    return {
        {"--model", "ID|FILE.glsl",
         "the model to fit: a built-in id (gonio models lists them) or a model file (docs/MODELS.md \"Your own "
         "model\"), whose own parameters param.NAME may be free; required",
         [&spec](const std::string& v) { spec.model = v; }},
        {"--free", "KEY[,KEY...]", "the stack keys the fit changes: layer.N.KEY or exterior_ior (required)",
         [&spec](const std::string& v) { spec.free = split_commas(v); }},
        {"--start", "KEY=V",
         "where the fit starts for a free key (default: the stack's value); repeatable, and repeated for one key "
         "the fit starts from each value (every combination over the keys, at most 64) and keeps the lowest loss",
         [&spec](const std::string& v) {
             const size_t eq = v.find('=');
             char* end = nullptr;
             const double x = eq == std::string::npos ? 0.0 : std::strtod(v.c_str() + eq + 1, &end);
             if (eq == std::string::npos || eq == 0 || end == v.c_str() + eq + 1 || *end != '\0' || !std::isfinite(x))
                 usage_error("--start: expected KEY=VALUE (e.g. --start layer.2.roughness=0.1), got '" + v + "'");
             spec.start.push_back({v.substr(0, eq), {x}});
         },
         false, true},
        {"--loss", "log|cosine|chi2",
         "what the fit minimises (default log: compare's remapped RMSE; cosine: the cosine-weighted L2 distance of f; "
         "chi2: the reference's own standard errors)",
         [&spec](const std::string& v) {
             try {
                 spec.loss = parse_fit_loss(v);
             } catch (const std::invalid_argument& e) { usage_error(std::string("--") + e.what()); }
         }},
        {"--without-bias-corrections", nullptr,
         "the fit as it was before its bias corrections (one descent, the log residual uncorrected): the negative "
         "control of gonio's calibration test",
         [&spec](const std::string&) { spec.bias_corrections = false; }, true},
    };
}

namespace {

OptionTable fit_options(FitSettings& a) {
    const OptionTable own = {
        {"--reference", "DIR",
         "fit to an earlier simulate / compare run (its DIR/state.gonio: its stack, angles and bins) instead of "
         "simulating; needs --out, takes no STACK and no other simulation option",
         [&a](const std::string& v) { a.reference = v; }},
        {"--no-report", nullptr, "no figures, no report.html", [&a](const std::string&) { a.no_report = true; }},
    };
    return walk_options(a.walk) + fit_spec_options(a.spec) + own;
}

}   // namespace

// The free keys, their starts and the model, checked against the stack before any work (exit 2 with the reason)
FitOptions checked_fit_options(const FitSpec& given, const Stack& s, bool progress) {
    if (given.model.empty()) usage_error("fit: --model ID (which model to fit)");
    if (given.free.empty()) usage_error("fit: --free KEY[,KEY...] (which stack keys it may change)");
    // a model file (its path ends in .glsl): read, checked and compiled now, and fitted by its id
    std::vector<std::shared_ptr<const UserModel>> users;
    FitSpec spec = given;
    if (spec.model.size() > 5 && spec.model.compare(spec.model.size() - 5, 5, ".glsl") == 0) {
        users.push_back(load_user_model(spec.model));
        spec.model = users.back()->header.id;
    }
    try {
        FitOptions fo = fit_options_for(s, spec, users);
        fo.progress = progress;
        return fo;
    } catch (const std::invalid_argument& e) { usage_error(std::string("fit: ") + e.what()); }
    return {};
}

namespace {

int run_fit(FitSettings& a, const std::vector<std::string>& operands) {
    const bool from_run = !a.reference.empty();
    SimResult r;
    std::optional<Case> run;
    std::string out, stack_name;
    if (from_run) {
        if (!operands.empty()) usage_error("fit: --reference DIR takes no STACK (the run's own is fitted)");
        for (const std::string& o : a.walk.given)
            if (o != "--out" && o != "--quiet" && o != "--device" && o != "--validate")
                usage_error("fit: " + o + " does not apply with --reference (the run's own options hold)");
        if (a.walk.out.empty()) usage_error("fit: --reference DIR needs --out OUT (the run's DIR is left as it is)");
        if (same_path(a.walk.out, a.reference))
            usage_error("fit: --out " + a.walk.out +
                        " is the reference's directory, which is left as it is: give "
                        "another");
        r = load_state(a.reference + "/state.gonio");
        out = a.walk.out;
        stack_name = a.reference + " (" + r.stack.name + ")";
    } else {
        stack_name = operands.empty() ? "" : operands[0];
        r.stack = stack_operand("fit", operands);
    }
    const FitOptions fo = checked_fit_options(a.spec, r.stack, a.walk.sim.progress);
    a.spec.model = fo.model;   // a model file's: its id
    VkContext ctx(a.walk.ctx);
    if (a.walk.sim.progress) std::fprintf(stderr, "gonio: device %s\n", ctx.device_info().name.c_str());
    if (!from_run) {
        run = prepare_run(a.walk, r.stack);
        r = simulate_gpu(ctx, run->stack, run->sim, run->resumed());
        out = run->out;
    }
    ModelEvaluator ev(ctx);
    FitResult f;
    try {
        f = fit_model(ev, r, r.stack, fo);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "gonio fit: %s\n", e.what());
        return 2;
    }
    // the reference's files with the model at the start and at the fit (id "ID@fit") as compare writes models
    std::vector<ModelSlices> slices{f.start_bins, f.best_bins};
    slices[1].id = a.spec.model + "@fit";
    const CaseResult cr{r, models_on_case(r, std::move(slices))};
    int rc = 0;
    if (run) {
        rc = write_case(*run, cr);
    } else {
        write_models_beside(out, r, *cr.models);
        rc = check_finite_json();
    }
    write_json_file(out + "/fit.json", fit_json(a.spec, stack_name, r, f, cr.models->comparison));
    std::printf("wrote %s/fit.json\n", out.c_str());
    if (!a.no_report) run_python_tool("report.py", out, "the figures and report.html");
    return std::max(rc, check_validation(ctx));
}

}   // namespace

Command fit_command() {
    return {
        "fit",
        "STACK.toml | --reference DIR  --model ID --free KEY[,KEY...] [--start KEY=V ...] [--loss log|cosine|chi2] [options]",
        "simulate, then find the values of the stack keys a model sees that bring it closest to the reference "
        "(standard errors from the reference's noise)",
        kFitNotes, invocation(&fit_options, &run_fit)};
}

}   // namespace gonio
