// in_process.cpp: see in_process.h.
#include "in_process.h"
#include "cmd_fit.h"
#include "cmd_render.h"
#include "sphere_stage.h"
#include "commands.h"
#include "fit_json.h"
#include "model_fit.h"
#include "common_options.h"
#include "help.h"
#include "json.h"
#include "node_files.h"
#include "pipeline_keeper.h"
#include "simulate_run.h"
#include "spectral_simulate.h"
#include "user_model.h"
#include "validation.h"
#include "vk_context.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <utility>

namespace gonio {

namespace {

// One Vulkan context per device and validation setting, made at the first run that asks for it and kept (never
// destroyed: a context torn down after the driver at the interpreter's exit would crash it), with its pipelines
// (pipeline_keeper.h: one run after another, lavapipe compiles each pipeline once). One run at a time uses the
// devices: Python threads, which run without the GIL, wait for it.
VkContext& context_for(const ContextOptions& o) {
    static std::map<std::pair<int, bool>, VkContext*> made;
    VkContext*& ctx = made[{o.device_index, o.validation}];
    if (!ctx) {
        ctx = new VkContext(o);
        keep_pipelines(*ctx->device());
    }
    return *ctx;
}

std::mutex& device_mutex() {
    static std::mutex m;
    return m;
}

// The device a run ran on, for what runs on it after (its models, a fit).
ContextOptions device_of(const InProcessRun& run) {
    ContextOptions o;
    o.device_index = run.device_index;
    return o;
}

// A validation message during the run: its failure (the command line's exit 1).
void check_device(const VkContext& ctx) {
    if (check_validation(ctx) != 0) throw std::runtime_error("the validation layer reported messages (stderr)");
}

// The options of a run in memory that would write files, refused with what to do instead.
void refuse_file_options(const std::vector<std::string>& args) {
    for (const std::string& a : args)
        if (a == "--out" || a == "--resume" || a == "--checkpoint-seconds")
            usage_error(a + ": a run in memory writes no files (save one with run.save(DIR))");
}

// args parsed by `table` as the command `name` parses its own; the stack is given, so no operand.
void parse_in_process(const std::string& name, const OptionTable& table, const std::vector<std::string>& args) {
    set_usage_command(name);
    const std::vector<std::string> operands = parse_options(command_named(name), table, args, commands());
    if (!operands.empty()) usage_error("'" + operands[0] + "': the stack is given, no operand is taken");
}

ModelSettings parse_model_settings(const std::vector<std::string>& args) {
    ModelSettings m;
    parse_in_process("compare", model_options(m), args);
    load_model_files(m, false);
    return m;
}

}   // namespace

InProcessRun run_in_process(const Stack& s, const std::vector<std::string>& args, bool compare,
                            const RunProgress& progress) {
    refuse_file_options(args);
    WalkSettings w;
    w.sim.progress = false;   // the caller's progress (a callback) instead of the console's line
    ModelSettings m;
    parse_in_process(compare ? "compare" : "simulate", compare ? walk_options(w) + model_options(m) : walk_options(w),
                     args);
    if (compare) load_model_files(m, false);
    InProcessRun run{plan_run(w, s), {}, w.ctx.device_index};
    run.planned.out.clear();
    run.planned.sim.on_progress = progress;
    std::lock_guard<std::mutex> lock(device_mutex());
    VkContext& ctx = context_for(w.ctx);
    run.result = run_case(ctx, run.planned, compare ? &m.models : nullptr);
    run.planned.sim.on_progress = nullptr;
    check_device(ctx);
    return run;
}

SpectralResult spectral_in_process(const Stack& s, const std::vector<std::string>& args, const RunProgress& progress) {
    refuse_file_options(args);
    WalkSettings w;
    w.sim.progress = false;
    SpectralBands bands;
    bool bands_given = false;
    parse_in_process("simulate", walk_options(w) + spectral_band_options(bands, bands_given, "--spectral"), args);
    if (w.sim.phi_i_deg != 0.0)
        usage_error("--phi-i goes with the RGB walk; --spectral takes the plane of incidence (phi_i 0)");
    Case run = plan_run(w, s);
    run.sim.on_progress = progress;
    std::lock_guard<std::mutex> lock(device_mutex());
    VkContext& ctx = context_for(w.ctx);
    int rc = 0;
    SpectralResult r = trace_spectral(run, bands, &ctx, 1, rc);
    check_device(ctx);
    if (rc != 0) throw std::runtime_error("paths booked a number that is not finite (a bug: please report it)");
    return r;
}

InProcessRender render_in_process(const Stack& s, const std::vector<std::string>& args, const RunProgress& progress) {
    refuse_file_options(args);
    for (const std::string& a : args)
        if (a == "--reference" || a == "--spectral" || a == "--no-report")
            usage_error(a + ": not taken by a render in memory (the table is traced now, in RGB; no report)");
    RenderSettings settings;
    parse_in_process("render", render_options(settings), args);
    check_render_settings(settings);
    const RenderRequest& a = settings.r;
    SphereStageRequest sr;   // as render_to_directory asks for it, with the table traced now
    sr.stack = &s;
    sr.env = a.env;
    sr.table_half = table_half_options(a);
    sr.table_half.on_progress = progress;   // the table's tracing (the models' stage is not looked at)
    sr.models = {a.size, a.spp, a.seed, a.models};
    sr.quiet = true;
    std::lock_guard<std::mutex> lock(device_mutex());
    VkContext& ctx = context_for(a.ctx);
    const SphereStage st = render_sphere_stage(ctx, sr);
    check_device(ctx);
    InProcessRender out;
    out.environment = st.env.name + " (" + st.env.source + ")";
    out.images = {{"reference", st.reference.image},
                  {"reference-half-a", st.reference.half[0]},
                  {"reference-half-b", st.reference.half[1]}};
    for (const ModelRender& m : st.models) {
        if (m.not_applicable.empty())
            out.images.emplace_back(m.id, m.image);
        else
            out.not_rendered.emplace_back(m.id, m.not_applicable);
    }
    return out;
}

InProcessRun with_models(const InProcessRun& run, const std::vector<std::string>& args, std::vector<ModelSlices> extra,
                         const std::vector<std::string>& glsl) {
    ModelSettings m = parse_model_settings(args);
    for (size_t i = 0; i < glsl.size(); ++i) {   // compiled as --model FILE is, and run beside the ids given
        m.models.user_models.push_back(compile_user_model(glsl[i], "<glsl " + std::to_string(i + 1) + ">"));
        if (!m.models.selected.empty() || args.empty())
            m.models.selected.push_back(m.models.user_models.back()->header.id);
    }
    check_model_ids(m.models);
    InProcessRun out{run.planned, {run.result.reference, std::nullopt}, run.device_index};
    const SimResult& ref = out.result.reference;
    std::vector<ModelCost> costs;
    std::optional<ModelStageCost> stage;
    std::vector<ModelSlices> slices;
    if (!args.empty() || extra.empty() || !glsl.empty()) {
        std::lock_guard<std::mutex> lock(device_mutex());
        VkContext& ctx = context_for(device_of(run));
        stage.emplace();
        slices = evaluate_models(ctx, ref.stack, model_grid(ref), &costs, m.models, &*stage);
        check_device(ctx);
    }
    for (ModelSlices& e : extra) slices.push_back(std::move(e));
    out.result.models = models_on_case(ref, std::move(slices), std::move(costs), stage);
    warn_energy_gains(ref, out.result.models->slices, out.result.models->comparison);
    return out;
}

namespace {

// k and the node count checked as gonio nodes checks them (k from 1 to 16, a count it would write).
void check_node_grid(const InProcessRun& run, int k) {
    if (k < 1 || k > kMaxNodesPerBinSide)
        usage_error("nodes per bin: k must be 1 to " + std::to_string(kMaxNodesPerBinSide) + " (k x k per bin), got " +
                    std::to_string(k));
    const SimResult& ref = run.result.reference;
    const ModelGrid g = model_grid(ref);
    const int sides = ref.stack.transmissive() ? 2 : 1;
    const std::string too_many = node_count_refusal(g.theta_i_deg.size(), sides, double(g.n_theta) * g.n_phi, k);
    if (!too_many.empty()) usage_error(too_many);
}

}   // namespace

std::vector<BinNode> run_nodes(const InProcessRun& run, int k) {
    check_node_grid(run, k);
    const SimResult& ref = run.result.reference;
    return bin_nodes(model_grid(ref), ref.stack.transmissive() ? 2 : 1, k);
}

ModelSlices node_model(const InProcessRun& run, const std::string& id, int k, const std::vector<glm::dvec3>& values) {
    if (!usable_model_id(id))
        usage_error("model id '" + id +
                    "' cannot name a model (not empty, not 'reference', no comma, quote or "
                    "control character)");
    check_node_grid(run, k);
    const SimResult& ref = run.result.reference;
    const ModelGrid g = model_grid(ref);
    const int sides = ref.stack.transmissive() ? 2 : 1;
    const size_t nodes = g.theta_i_deg.size() * size_t(sides) * g.n_theta * g.n_phi * size_t(k) * size_t(k);
    if (values.size() != nodes)
        usage_error(id + ": " + std::to_string(values.size()) + " values for " + std::to_string(nodes) +
                    " nodes (one row r, g, b per node, in the nodes' order)");
    size_t bad = 0, first_bad = 0;
    for (size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!usable_model_value(values[i][c]))
                if (bad++ == 0) first_bad = i;
    if (bad > 0)   // as gonio score refuses such a values file
        usage_error(id + ": " + std::to_string(bad) +
                    " values are negative, NaN, infinite or beyond the largest float (3.4e38: the bins hold floats; "
                    "the first at node " +
                    std::to_string(first_bad) + "): a BRDF is finite and non-negative; nothing is clamped");
    ModelSlices m = slices_from_node_values(id, g, sides, k, values);
    m.file = "(values)";   // a user's model: its energy measured, its reciprocity not (gonio does not run it)
    return m;
}

InProcessFit fit_in_process(const InProcessRun& run, const std::vector<std::string>& args) {
    FitSpec spec;
    parse_in_process("fit", fit_spec_options(spec), args);
    const SimResult& ref = run.result.reference;
    const FitOptions fo = checked_fit_options(spec, ref.stack, false);
    spec.model = fo.model;   // a model file's: its id
    std::lock_guard<std::mutex> lock(device_mutex());
    VkContext& ctx = context_for(device_of(run));
    ModelEvaluator ev(ctx);
    const FitResult f = fit_model(ev, ref, ref.stack, fo);
    check_device(ctx);
    std::vector<ModelSlices> slices{f.start_bins, f.best_bins};
    slices[1].id = spec.model + "@fit";
    InProcessFit out{{run.planned, {ref, models_on_case(ref, std::move(slices))}, run.device_index}, ""};
    out.fit_json = json_text(fit_json(spec, ref.stack.source_path, ref, f, out.run.result.models->comparison));
    return out;
}

std::string run_summary_text(const InProcessRun& run) { return json_text(case_summary_json(run.result)); }

std::string run_slices_text(const InProcessRun& run) { return case_slices_csv(run.result); }

void save_run(const InProcessRun& run, const std::string& dir) {
    std::filesystem::create_directories(dir);
    write_case_files(dir, run.result);
}

std::string command_help_text(const std::string& command) { return command_help(command_named(command)); }

}   // namespace gonio
