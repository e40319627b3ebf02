// gonio: a virtual gonio-photometer for layered materials. Command-line entry point.
#include "cmd_bench.h"
#include "compare.h"
#include "histogram.h"
#include "json.h"
#include "lambertian_series.h"
#include "models.h"
#include "output.h"
#include "python_tool.h"
#include "random_stack.h"
#include "reference.h"
#include "stack.h"
#include "state.h"
#include "sweep.h"
#include "text_format.h"
#include "vk_context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace gonio;

namespace {

// The help, in sections: `gonio --help` prints them all, `gonio COMMAND --help` the command's own.
const char* kHelpTitle = "gonio " GONIO_VERSION " - a virtual gonio-photometer for layered materials (Vulkan compute)\n";
const char* kHelpUsage = R"(
usage:
  gonio devices                         list Vulkan devices; '*' marks the one gonio uses
  gonio check STACK.toml                parse and validate a stack file, print it, exit
  gonio simulate STACK.toml [options]   trace paths through the stack, write calibrated BRDF/BTDF histograms
  gonio compare STACK.toml [options]    simulate, then evaluate every analytic model that can represent the
                                        stack on the same bins, and write how far each is from the reference
  gonio models                          list the models: id, citation, which stacks each can represent
  gonio bench [STACK.toml ...] [options]
                                        paths per second per stack on the device and on the CPU twin
                                        (default: every stacks/*.toml); --out DIR adds convergence, the
                                        models' cost against their error, and an error atlas
  gonio random-stack --seed N [--count K] [--out DIR]
                                        seeded random stacks over the whole valid parameter space, as
                                        TOML (stdout, or DIR/random-N-i.toml); same seed, same stacks
  gonio sweep SWEEP.toml [--out DIR] [--shard K/N] [--resume] [--batch B] [--bench N] [--keep-results] [--quiet]
                                        vary stack parameters (sweeps/*.toml), run the reference and every
                                        model per configuration, and tabulate their errors in DIR/sweep.csv;
                                        --batch: configurations traced per dispatch (default 16; results do not
                                        depend on it); --bench N: time N configurations batched and as a loop
                                        of compare, in one run (DIR/sweep-bench.json); --keep-results: also
                                        each configuration's EXR, slices.csv and summary.json (DIR/configs/c-N/).
                                        A sweep file gives paths per configuration and angle, or rse = R (each
                                        configuration runs as simulate --rse R, paths then the cap)
  gonio merge DIR                       gather the shards of a sweep (DIR/configs/) into DIR/sweep.csv
  gonio view STACK.toml [options]       the interactive viewer (a window; runs gonio-view, built beside
                                        gonio when GLFW and Dear ImGui are installed; gonio view --help)
  gonio help | --help                   this text

)";
const char* kHelpSimulate = R"(simulate options:
  --theta-i A,B,...     incident polar angles in degrees, in [0, 90)           (default 0)
  --paths N             paths per incident angle, e.g. 1e8                     (default 1e6)
  --seed S              random seed (same seed, same bytes)                    (default 1)
  --out DIR             output directory                                       (default out/<stack name>)
  --dtheta D --dphi P   bin widths in degrees; D divides 90, P divides 180     (default 1, 2)
  --orders              also split the histograms by path class: 0 = top reflection only / direct
                        transmission, 1 = one internal reversal (one trip to the base and back),
                        2 = two or more (inter-reflections). Classes sum exactly to the total.
  --max-events N        event cap per path; energy still inside is reported as truncated (default 256)
  --rse R               run until the relative standard errors of the bins above 1% of their slice's peak
                        are below R (e.g. 0.01) at the --rse-quantile; paths grow in rounds of 2^20 x 2^k
                        per angle, --paths is the cap (default then 1e10). summary.json says what stopped
                        each angle, and the median, 90th percentile and worst relative se
  --rse-quantile Q      which bins --rse stops on: the quantile Q of their relative standard errors
                        (default 0.5, the median; 1: the worst bin, which can take hours)
  --checkpoint-seconds S  write DIR/state.gonio atomically at least every S seconds of tracing (default 30;
                        0: only at the end): a killed run continues with the same command and --resume DIR,
                        to the same bytes as one uninterrupted run
  --max-seconds S       stop an incident angle after S seconds (reported as stopped_by max_seconds)
  --resume DIR          continue the run whose output is in DIR (its state.gonio) up to --paths: the result
                        is exactly that of one longer run. Same stack, seed, bins, angles, options required
  --cpu-twin            run the walk on the CPU (same shader sources via GLM) instead of the device
  --general-walk        use the general N-layer walk instead of the stack-specialised shader
  --no-series           trace every trip between a Lambertian base and its coat instead of summing them
                        as the Lambertian series (docs/PHYSICS.md; the default where it applies: a
                        dielectric coat over a Lambertian base, without --orders)
  --no-baked-stack      read the stack's parameters from a uniform buffer at run time instead of compiling
                        them into the shader (the default for a specialised walk of one or two layers;
                        docs/PERFORMANCE.md). The same paths and estimator; the last bits of rounding can
                        differ, and this is what a sweep's batches compute: use it to reproduce one
                        configuration of a sweep byte for byte
  --device I            Vulkan device index (see `gonio devices`)
  --validate            enable the Khronos validation layer; any message makes the run fail
  --quiet               no progress line

)";
const char* kHelpSimulateOutputs = R"(simulate writes, in DIR:
  <name>.exr      OpenEXR, one part per incident angle and side (R: reflection, T: transmission);
                  rows = theta bins, columns = phi bins (centred on multiples of dphi); channels R,G,B
                  (bin average of f, 1/sr) and se.R, se.G, se.B (standard errors); header: stack, angles,
                  paths, seed, device, gonio version
  slices.csv      one row per bin: source,theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b
  summary.json    per incident angle and channel: reflected, transmitted, absorbed, microfacet_loss and
                  truncated energy fractions (they sum to 1); paths, seconds, paths per second, device

)";
const char* kHelpCompare = R"(compare options (and the simulate options above, but --cpu-twin):
  --no-report           no figures, no report.html
  --no-belcour-tables   Belcour's models without their FGD and TIR tables (see below)

compare writes everything simulate writes, plus: model rows in slices.csv (source = model id, reflection
side, se 0), and in summary.json per model and incident angle: RMSE and mean absolute error in the seed's
remapped space log(1 + sqrt f), RMSE and mean relative error in f, directional albedo (model, reference,
error), the largest remapped error and its bin, the reference's own noise on the same bins (remapped), and
whether the model is within that noise, and whether its albedo (reflected + transmitted) breaks the white-furnace
bound (reflects_more_than_it_receives: flagged and warned on stderr, never clamped). A model that cannot represent
the stack is listed with the reason.
It then draws, with tools/report.py (Python 3 + matplotlib): slices.png (the seed's in-plane slice diagrams,
log(1 + sqrt f) of luminance), albedo.png, topview-<i>.png (top view of the hemisphere: reference, models,
signed differences), and report.html with the metric tables. --no-report skips them.
--no-belcour-tables runs Belcour's models without their FGD and TIR tables (Fresnel at the mean cosine, no TIR
term), as the seed does for slabs. The tables are computed on the device for the stack's interfaces and cached in
$GONIO_CACHE_DIR (default $XDG_CACHE_HOME/gonio or ~/.cache/gonio; GONIO_NO_CACHE=1 turns the cache off).

)";
const char* kHelpBench = R"(bench options: --paths N (device, default 2e7), --cpu-paths N (default 1e6), --theta-i A, --device I,
  --out DIR: also measure, per stack, the reference's convergence (relative RMS error against a 2^25-path run
  and median relative standard error, against paths and seconds, with the 1/sqrt(N) fit and the seconds to
  reach 1% and 0.1%), and every model on the 2^25-path run's bins (device seconds per evaluation and per
  grid against its RMSE in log(1 + sqrt f)); then the error atlas: --atlas K random two-layer stacks (a coat
  over a conductor; default 16, 0: none; --seed picks them), the reference (--atlas-paths per angle, default
  2e6) and every model at 0/30/60/80 degrees, the best model per stack and angle. Writes DIR/bench.json,
  convergence.png, pareto.png, atlas.png and bench.html (tools/bench_plot.py).
  Prints, per stack, paths per second of the stack-specialised walk, of the general N-layer walk, and of
  the CPU twin (same shader sources, all cores), measured in one run, with their ratios.

)";
const char* kHelpRandomStack = R"(random-stack options: --seed N (default 1), --count K (default 1), --out DIR (default: print to stdout)

)";
const char* kHelpTail = R"(Exit codes: 0 success; 2 refused input (a stack, sweep or state file that is invalid, with file:line, or an
option that cannot work; nothing is run); 1 a failure while running (a device error, a write that failed, a
Vulkan validation message under --validate, paths whose weight stopped being finite).

Conventions (docs/PHYSICS.md): directions point away from the surface, z is the stack normal, the light
arrives from (theta_i, phi_i = 0); f excludes the cosine.
)";


[[noreturn]] void usage_error(const std::string& msg) {
    std::fprintf(stderr, "gonio: %s\n(run `gonio --help` for usage)\n", msg.c_str());
    std::exit(2);
}

double parse_number(const std::string& opt, const std::string& v) {
    char* end = nullptr;
    double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(d)) usage_error(opt + ": expected a number, got '" + v + "'");
    return d;
}

uint64_t parse_count(const std::string& opt, const std::string& v) {
    double d = parse_number(opt, v);
    if (d < 0 || d != std::floor(d) || d > 1.8e19) usage_error(opt + ": expected a whole non-negative number, got '" + v + "'");
    return uint64_t(d);
}

std::vector<double> parse_list(const std::string& opt, const std::string& v) {
    std::vector<double> out;
    size_t i = 0;
    while (i <= v.size()) {
        size_t j = v.find(',', i);
        if (j == std::string::npos) j = v.size();
        out.push_back(parse_number(opt, v.substr(i, j - i)));
        i = j + 1;
    }
    return out;
}

struct Args {
    std::vector<std::string> positional;
    SimOptions sim;
    ContextOptions ctx;
    std::string out;
    bool cpu_twin = false;
    uint64_t cpu_paths = 1000000;
    bool paths_given = false;
    bool no_report = false;
    ModelOptions models;
    std::string resume;
    uint64_t count = 1;               // random-stack
    uint64_t atlas = 16;              // bench --out: random stacks in the error atlas
    uint64_t atlas_paths = 2000000;
    double checkpoint_seconds = 30.0;  // simulate / compare: the state file written at least this often
};

// Which options each command takes (sweep, merge and view parse their own): anything else is refused.
const std::vector<std::pair<std::string, std::vector<std::string>>>& command_options() {
    static const std::vector<std::string> walk = {"--theta-i", "--paths", "--seed", "--out", "--dtheta", "--dphi", "--orders",
                                                  "--max-events", "--rse", "--rse-quantile", "--max-seconds", "--resume",
                                                  "--checkpoint-seconds", "--general-walk", "--no-series", "--no-baked-stack",
                                                  "--device", "--validate", "--quiet", "--invalid-path-for-tests"};
    static const std::vector<std::pair<std::string, std::vector<std::string>>> t = [] {
        std::vector<std::string> simulate = walk, compare = walk;
        simulate.push_back("--cpu-twin");
        compare.insert(compare.end(), {"--no-report", "--no-belcour-tables"});
        return std::vector<std::pair<std::string, std::vector<std::string>>>{
            {"simulate", simulate},
            {"compare", compare},
            {"bench", {"--theta-i", "--paths", "--cpu-paths", "--seed", "--out", "--dtheta", "--dphi", "--max-events", "--atlas",
                       "--atlas-paths", "--no-belcour-tables", "--general-walk", "--no-series", "--no-baked-stack", "--device",
                       "--validate", "--quiet"}},
            {"random-stack", {"--seed", "--count", "--out"}},
            {"check", {}},
            {"models", {}},
            {"devices", {}},
        };
    }();
    return t;
}

// What `gonio COMMAND --help` prints.
std::string command_help(const std::string& cmd) {
    std::string usage_line, l;
    std::istringstream in(kHelpUsage);
    bool mine = false;   // a command's block: its "  gonio CMD" line and the indented lines under it
    while (std::getline(in, l)) {
        if (l.rfind("  gonio ", 0) == 0) mine = l.rfind("  gonio " + cmd + " ", 0) == 0 || l == "  gonio " + cmd;
        else if (l.rfind("      ", 0) != 0) mine = false;
        if (mine) usage_line += l + "\n";
    }
    std::string h = std::string(kHelpTitle) + "\nusage:\n" + usage_line + "\n";
    if (cmd == "simulate") h += std::string(kHelpSimulate) + kHelpSimulateOutputs;
    else if (cmd == "compare") h += std::string(kHelpSimulate) + kHelpCompare;
    else if (cmd == "bench") h += kHelpBench;
    else if (cmd == "random-stack") h += kHelpRandomStack;
    else if (cmd == "check" || cmd == "models" || cmd == "devices") h += "(no options)\n\n";
    return h + kHelpTail;
}

Args parse_args(const std::string& cmd, int argc, char** argv, int first) {
    Args a;
    a.sim.progress = true;
    const std::vector<std::string>* allowed = nullptr;
    for (auto& [c, opts] : command_options())
        if (c == cmd) allowed = &opts;
    for (int i = first; i < argc; ++i) {
        std::string s = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage_error(s + " needs a value");
            return argv[++i];
        };
        if (s.rfind("--", 0) == 0 && allowed && std::find(allowed->begin(), allowed->end(), s) == allowed->end()) {
            bool known = false;
            for (auto& [c, opts] : command_options()) known |= std::find(opts.begin(), opts.end(), s) != opts.end();
            std::string list;
            for (auto& o : *allowed)
                if (o != "--invalid-path-for-tests") list += (list.empty() ? "" : " ") + o;
            usage_error((known ? "option " + s + " does not apply to `gonio " + cmd + "`"
                               : "unknown option " + s + " for `gonio " + cmd + "`") +
                        (list.empty() ? " (it takes no options)" : " (its options: " + list + ")"));
        }
        if (s == "--theta-i") {
            a.sim.theta_i_deg = parse_list(s, value());
            // the library takes an angle twice (independent replicates: each angle index has its own stream), but
            // the outputs name their parts by angle
            for (size_t k = 0; k < a.sim.theta_i_deg.size(); ++k)
                for (size_t j = 0; j < k; ++j)
                    if (a.sim.theta_i_deg[k] == a.sim.theta_i_deg[j])
                        usage_error("--theta-i: the incident angle " + format_g9(a.sim.theta_i_deg[k]) + " is given twice");
        }
        else if (s == "--paths") { a.sim.paths = parse_count(s, value()); a.paths_given = true; }
        else if (s == "--cpu-paths") a.cpu_paths = parse_count(s, value());
        else if (s == "--seed") {
            uint64_t v = parse_count(s, value());
            if (v > 0xffffffffull) usage_error("--seed must fit in 32 bits");
            a.sim.seed = uint32_t(v);
        }
        else if (s == "--out") a.out = value();
        else if (s == "--dtheta") a.sim.dtheta_deg = parse_number(s, value());
        else if (s == "--dphi") a.sim.dphi_deg = parse_number(s, value());
        else if (s == "--orders") a.sim.orders = true;
        else if (s == "--max-events") {
            uint64_t v = parse_count(s, value());
            if (v > 1000000) usage_error("--max-events too large");
            a.sim.max_events = uint32_t(v);
        }
        else if (s == "--cpu-twin") a.cpu_twin = true;
        else if (s == "--rse") {
            a.sim.rse_target = parse_number(s, value());
            if (!(a.sim.rse_target > 0 && a.sim.rse_target < 1)) usage_error("--rse must be in (0, 1), e.g. 0.01");
        }
        else if (s == "--rse-quantile") {
            a.sim.rse_quantile = parse_number(s, value());
            if (!(a.sim.rse_quantile > 0 && a.sim.rse_quantile <= 1)) usage_error("--rse-quantile must be in (0, 1], e.g. 0.5 (the median) or 1 (the worst bin)");
        }
        else if (s == "--checkpoint-seconds") {
            a.checkpoint_seconds = parse_number(s, value());
            if (!(a.checkpoint_seconds >= 0)) usage_error("--checkpoint-seconds must be at least 0 (0: no checkpoints)");
        }
        else if (s == "--max-seconds") {
            a.sim.max_seconds = parse_number(s, value());
            if (!(a.sim.max_seconds > 0)) usage_error("--max-seconds must be positive");
        }
        else if (s == "--resume") a.resume = value();
        else if (s == "--count") a.count = parse_count(s, value());
        else if (s == "--atlas") a.atlas = parse_count(s, value());
        else if (s == "--atlas-paths") a.atlas_paths = parse_count(s, value());
        else if (s == "--no-report") a.no_report = true;
        else if (s == "--no-belcour-tables") a.models.belcour_tables = false;
        else if (s == "--general-walk") a.sim.specialised = false;
        else if (s == "--no-series") a.sim.series = false;
        else if (s == "--no-baked-stack") a.sim.baked_stack = false;
        else if (s == "--device") a.ctx.device_index = int(parse_count(s, value()));
        else if (s == "--validate") a.ctx.validation = true;
        else if (s == "--quiet") a.sim.progress = false;
        else if (s == "--invalid-path-for-tests") {   // undocumented: gonio's tests of the invalid class
            uint64_t v = parse_count(s, value());
            if (v >= 0xffffffffull) usage_error("--invalid-path-for-tests: a path index below 2^32 - 1");
            a.sim.invalid_path_for_tests = uint32_t(v);
        }
        else if (s.rfind("--", 0) == 0) usage_error("unknown option " + s);
        else a.positional.push_back(s);
    }
    return a;
}

int cmd_devices() {
    auto devs = VkContext::list_devices();
    if (devs.empty()) { std::printf("no Vulkan devices\n"); return 1; }
    int chosen = -1;
    try { VkContext ctx({}); chosen = int(ctx.device_info().index); } catch (const std::exception& e) {
        std::fprintf(stderr, "gonio: %s\n", e.what());
    }
    for (auto& d : devs) {
        std::printf("%c %u: %s (%s; %s; Vulkan %u.%u)%s%s\n", int(d.index) == chosen ? '*' : ' ', d.index, d.name.c_str(),
                    d.type.c_str(), d.driver.c_str(), VK_API_VERSION_MAJOR(d.api_version), VK_API_VERSION_MINOR(d.api_version),
                    d.usable ? "" : "  [unusable: ", d.usable ? "" : (d.why_not + "]").c_str());
    }
    return chosen >= 0 ? 0 : 1;
}

int cmd_check(const Args& a) {
    if (a.positional.size() != 1) usage_error("check takes one stack file");
    Stack s = parse_stack_file(a.positional[0]);
    std::printf("%s", describe_stack(s).c_str());
    // which walk simulate runs on it (docs/PHYSICS.md, "The Lambertian series")
    const LambertianSeries ls = lambertian_series(s);
    if (ls.applies)
        std::printf("  walk: the Lambertian series (one trip traced, the others summed: S = %.4g, %.4g, %.4g; quadrature "
                    "error bound %.1e relative)\n", ls.gain.x, ls.gain.y, ls.gain.z, ls.relative_error);
    else
        std::printf("  walk: every trip traced (no Lambertian series: %s)\n", ls.reason.c_str());
    std::printf("ok: %s is a valid stack\n", a.positional[0].c_str());
    return 0;
}

int check_validation(const VkContext& ctx) {
    if (ctx.validation_messages() > 0) {
        std::fprintf(stderr, "gonio: %llu Vulkan validation message(s): failing\n",
                     (unsigned long long)ctx.validation_messages());
        return 1;
    }
    return 0;
}

// Figures and report.html of a compare run, by tools/report.py.
void make_report(const std::string& out) { run_python_tool("report.py", out, "the figures and report.html"); }

int cmd_models() {
    for (size_t i = 0; i < model_registry().size(); ++i) {
        const ModelInfo& m = model_registry()[i];
        std::printf("%-26s %s\n%-26s   %s\n%-26s   represents: %s; %s\n%-26s   %s%s\n", m.id.c_str(), m.citation.c_str(), "",
                    m.summary.c_str(), "", m.represents.c_str(), m.reciprocal ? "reciprocal" : "not reciprocal", "",
                    m.energy_conserving ? "energy-conserving" : "not energy-conserving by construction: ",
                    m.energy_conserving ? "" : m.energy_note.c_str());
    }
    return 0;
}

int cmd_simulate(const Args& a, bool compare) {
    if (a.positional.size() != 1) usage_error(std::string(compare ? "compare" : "simulate") + " takes one stack file");
    Stack s = parse_stack_file(a.positional[0]);
    Args args = a;
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
            models = evaluate_models(ctx, s, model_grid(r), &costs, a.models, &stage);
            models_summary = models_json(r, models, costs, &stage);
            warn_energy_gains(r, models);
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
            std::fprintf(stderr, "gonio: theta_i %g: %.0f paths booked a number that is not finite (summary.json: energy "
                                 "invalid %.3g): a bug, please report it with the stack file and the command\n",
                         r.angles[i].theta_i_deg, e.invalid.x * double(r.angles[i].paths), e.invalid.x);
            rc = 1;
        }
        std::printf("theta_i %5g: R %.5f %.5f %.5f  T %.5f %.5f %.5f  %llu paths (%s), median rse %.4f, worst %.4f\n",
                    r.angles[i].theta_i_deg, e.reflected.x, e.reflected.y, e.reflected.z, e.transmitted.x,
                    e.transmitted.y, e.transmitted.z, (unsigned long long)r.angles[i].paths,
                    r.angles[i].stopped_by.c_str(), r.angles[i].median_rse, r.angles[i].worst_rse);
    }
    for (const ModelSlices& m : models) {
        if (!m.not_applicable.empty()) {
            std::printf("%-26s not applicable: %s\n", m.id.c_str(), m.not_applicable.c_str());
            continue;
        }
        std::printf("%-26s", m.id.c_str());
        for (size_t i = 0; i < m.f.size(); ++i) {
            ModelMetrics mm = compare_model(r, i, m.f[i]);
            std::printf("  theta_i %g: rmse %.4f chi2/dof %.3g%s", r.angles[i].theta_i_deg, mm.rmse_remapped,
                        mm.agreement.chi2_per_dof, mm.within_noise ? " (within noise)" : "");
            if (i < m.t.size()) {
                ModelMetrics mt = compare_model(r, i, m.t[i], kTransmission);
                std::printf(" T %.4f chi2/dof %.3g%s", mt.rmse_remapped, mt.agreement.chi2_per_dof, mt.within_noise ? " (within noise)" : "");
            }
        }
        std::printf("   (remapped log(1+sqrt f))\n");
    }
    std::printf("wrote %s/{%s.exr,slices.csv,summary.json,state.gonio}\n", out.c_str(), safe_file_name(s.name).c_str());
    if (non_finite_json_numbers() > 0) {
        std::fprintf(stderr, "gonio: %llu numbers of summary.json were not finite (written as null): a bug, please report it\n",
                     (unsigned long long)non_finite_json_numbers());
        rc = 1;
    }
    if (compare && !a.no_report) make_report(out);
    return rc;
}

int cmd_bench(const Args& a) {
    BenchOptions b;
    b.stacks = a.positional;
    b.sim = a.sim;
    if (!a.paths_given) b.sim.paths = 20000000;
    b.cpu_paths = a.cpu_paths;
    b.ctx = a.ctx;
    b.models = a.models;
    b.out = a.out;
    if (a.atlas > 10000) usage_error("--atlas: at most 10000 stacks");
    b.atlas_stacks = uint32_t(a.atlas);
    if (a.atlas_paths < 1) usage_error("--atlas-paths must be at least 1");
    b.atlas_paths = a.atlas_paths;
    if (b.sim.theta_i_deg.size() != 1) usage_error("bench takes one --theta-i");
    return gonio::cmd_bench(b);
}

// gonio random-stack: seeded random stacks, each checked by parsing its own text back.
int cmd_random_stack(const Args& a) {
    if (!a.positional.empty()) usage_error("random-stack takes no positional arguments (--seed N --count K --out DIR)");
    if (a.count < 1 || a.count > 100000) usage_error("--count must be in [1, 100000]");
    if (!a.out.empty()) fs::create_directories(a.out);
    for (uint64_t i = 0; i < a.count; ++i) {
        std::string text = random_stack_toml(a.sim.seed, i);
        Stack s = parse_stack_string(text, "random-stack");   // what `gonio check` will read
        if (a.out.empty()) {
            std::printf("%s%s", i ? "\n# ----\n" : "", text.c_str());
        } else {
            std::string path = a.out + "/" + safe_file_name(s.name) + ".toml";
            std::ofstream(path) << text;
            std::printf("wrote %s (%zu layers)\n", path.c_str(), s.layers.size());
        }
    }
    return 0;
}

// gonio sweep: its own options (--resume takes no value here).
int cmd_sweep(int argc, char** argv) {
    std::string file, out;
    SweepRunOptions o;
    uint64_t bench = 0;
    ContextOptions ctx_opt;
    for (int i = 2; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--out") out = value();
        else if (a == "--shard") {
            try { o.shard = parse_shard(value()); } catch (const std::invalid_argument& e) { usage_error(e.what()); }
        }
        else if (a == "--resume") o.resume = true;
        else if (a == "--keep-results") o.keep_results = true;
        else if (a == "--quiet") o.progress = false;
        else if (a == "--device") ctx_opt.device_index = int(parse_count(a, value()));
        else if (a == "--validate") ctx_opt.validation = true;
        else if (a == "--no-belcour-tables") o.models.belcour_tables = false;
        else if (a == "--batch") {
            uint64_t v = parse_count(a, value());
            if (v < 1 || v > 4096) usage_error("--batch must be in [1, 4096]");
            o.batch = uint32_t(v);
        }
        else if (a == "--bench") bench = parse_count(a, value());
        else if (a.rfind("--", 0) == 0) usage_error("unknown option " + a + " for sweep");
        else if (file.empty()) file = a;
        else usage_error("sweep takes one sweep file");
    }
    if (file.empty()) usage_error("sweep: no sweep file (see sweeps/*.toml)");
    Sweep sw = parse_sweep_file(file);
    if (out.empty()) out = "out/sweep-" + safe_file_name(sw.name);
    VkContext ctx(ctx_opt);
    if (bench > 0) {
        const Json json = bench_sweep(ctx, sw, bench, o.models);
        fs::create_directories(out);
        write_json_file(out + "/sweep-bench.json", json);
        std::printf("%swrote %s/sweep-bench.json\n", json_text(json).c_str(), out.c_str());
        return check_validation(ctx);
    }
    uint64_t n = run_sweep(ctx, sw, out, o);
    std::printf("sweep %s: %llu configurations computed in shard %llu/%llu (%llu in the sweep) -> %s/configs/\n", sw.name.c_str(),
                (unsigned long long)n, (unsigned long long)o.shard.index, (unsigned long long)o.shard.count,
                (unsigned long long)sw.configurations(), out.c_str());
    if (o.shard.count == 1) {
        uint64_t rows = merge_sweep(out);
        std::printf("wrote %s/sweep.csv (%llu rows) and timings.csv\n", out.c_str(), (unsigned long long)rows);
        run_python_tool("sweep_plot.py", out, "the sweep figures");
    }
    return check_validation(ctx);
}

int cmd_merge(int argc, char** argv) {
    if (argc != 3) usage_error("merge takes one sweep output directory");
    uint64_t rows = merge_sweep(argv[2]);
    std::printf("wrote %s/sweep.csv (%llu rows) and timings.csv\n", argv[2], (unsigned long long)rows);
    run_python_tool("sweep_plot.py", argv[2], "the sweep figures");
    return 0;
}

// gonio view ...: the viewer is its own binary (so that gonio needs no display libraries); run it.
int cmd_view(int argc, char** argv) {
    std::error_code ec;
    fs::path self = fs::read_symlink("/proc/self/exe", ec);
    fs::path viewer = (ec ? fs::path(argv[0]) : self).parent_path() / "gonio-view";
    if (!fs::exists(viewer)) {
        std::fprintf(stderr, "gonio view: the viewer was not built (%s is missing): it needs GLFW and Dear ImGui "
                             "(Debian: apt-get install libglfw3-dev libimgui-dev libstb-dev), then ./run build\n",
                     viewer.c_str());
        return 1;
    }
    std::vector<char*> args{const_cast<char*>(viewer.c_str())};
    for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    execv(viewer.c_str(), args.data());
    std::fprintf(stderr, "gonio view: cannot run %s: %s\n", viewer.c_str(), std::strerror(errno));
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::printf("%s\n%s%s", kHelpTitle, kHelpUsage, kHelpTail);
        return 2;
    }
    std::string cmd = argv[1];
    try {
        if (cmd == "help" || cmd == "--help" || cmd == "-h") {
            std::printf("%s\n%s%s%s%s%s%s%s%s", kHelpTitle, kHelpUsage, kHelpSimulate, kHelpSimulateOutputs, kHelpCompare, kHelpBench,
                        kHelpRandomStack, "", kHelpTail);
            return 0;
        }
        if (cmd == "--version") { std::printf("gonio %s\n", GONIO_VERSION); return 0; }
        if (cmd != "view")   // gonio COMMAND --help: the full help (the viewer has its own)
            for (int i = 2; i < argc; ++i)
                if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
                    std::fputs(command_help(cmd).c_str(), stdout);
                    return 0;
                }
        if (cmd == "sweep") return cmd_sweep(argc, argv);
        if (cmd == "merge") return cmd_merge(argc, argv);
        if (cmd == "view") return cmd_view(argc, argv);
        Args a = parse_args(cmd, argc, argv, 2);
        if (cmd == "devices") return cmd_devices();
        if (cmd == "check") return cmd_check(a);
        if (cmd == "simulate") return cmd_simulate(a, false);
        if (cmd == "compare") return cmd_simulate(a, true);
        if (cmd == "models") return cmd_models();
        if (cmd == "bench") return cmd_bench(a);
        if (cmd == "random-stack") return cmd_random_stack(a);
        usage_error("unknown command '" + cmd + "'");
    } catch (const StackError& e) {   // a refused input file: exit 2
        std::fprintf(stderr, "gonio: %s\n", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {   // a refused option or input (checked before any work): exit 2
        std::fprintf(stderr, "gonio: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {   // a failure while running: exit 1
        std::fprintf(stderr, "gonio: error: %s\n", e.what());
        return 1;
    }
}
