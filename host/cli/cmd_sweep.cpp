#include "cmd_sweep.h"
#include "common_options.h"
#include "json.h"
#include "output.h"
#include "python_tool.h"
#include "spectral_sweep.h"
#include "sweep.h"
#include "user_model.h"
#include "validation.h"
#include "vk_context.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace gonio {

namespace {

struct SweepSettings {
    std::string out;
    SweepRunOptions run;
    uint64_t bench = 0;   // --bench N: time N configurations instead of running the sweep
    bool batch_given = false;
    ContextOptions ctx;
};

// --resume takes no value here: a sweep's directory is --out.
OptionTable sweep_options(SweepSettings& a) {
    SweepRunOptions& o = a.run;
    return {
        {"--out", "DIR", "output directory (default out/sweep-<sweep name>)",
         [&a](const std::string& v) { a.out = v; }},
        {"--shard", "K/N",
         "compute only the K-th of N shares of the configurations (a Slurm job array's task); gonio merge DIR "
         "gathers the shards",
         [&o](const std::string& v) {
             try {
                 o.shard = parse_shard(v);
             } catch (const std::invalid_argument& e) { usage_error(e.what()); }
         }},
        {"--resume", nullptr, "skip the configurations DIR/configs/ already holds (a killed run continues)",
         [&o](const std::string&) { o.resume = true; }},
        {"--batch", "B", "configurations traced per dispatch, 1 to 4096 (default 16; results do not depend on it)",
         [&o, &a](const std::string& v) {
             const uint64_t n = parse_count("--batch", v);
             if (n < 1 || n > 4096) usage_error("--batch must be in [1, 4096]");
             o.batch = uint32_t(n);
             a.batch_given = true;
         }},
        {"--bench", "N",
         "time N configurations batched and as a loop of compare, in one run (DIR/sweep-bench.json), instead of "
         "running the sweep",
         [&a](const std::string& v) { a.bench = parse_count("--bench", v); }},
        {"--keep-results", nullptr,
         "also write each configuration's EXR, slices.csv and summary.json (DIR/configs/c-N/)",
         [&o](const std::string&) { o.keep_results = true; }},
        {"--no-belcour-tables", nullptr, "Belcour's models without their FGD and TIR tables (as for compare)",
         [&o](const std::string&) { o.models.belcour_tables = false; }},
        device_option(a.ctx),
        validate_option(a.ctx),
        {"--quiet", nullptr, "no progress line", [&o](const std::string&) { o.progress = false; }},
    };
}

int bench_sweep_only(VkContext& ctx, const Sweep& sw, const SweepSettings& a, const std::string& out) {
    const Json json = bench_sweep(ctx, sw, a.bench, a.run.models);
    fs::create_directories(out);
    write_json_file(out + "/sweep-bench.json", json);
    std::printf("%swrote %s/sweep-bench.json\n", json_text(json).c_str(), out.c_str());
    return check_validation(ctx);
}

int run_sweep_command(SweepSettings& a, const std::vector<std::string>& operands) {
    if (operands.empty()) usage_error("sweep: no sweep file (see sweeps/*.toml)");
    if (operands.size() > 1) usage_error("sweep takes one sweep file");
    SweepRunOptions& o = a.run;
    Sweep sw = parse_sweep_file(operands[0]);
    // the sweep's model files, compiled before any configuration runs (a compile error: FILE:LINE, exit 2)
    for (const std::string& f : sw.model_files) o.models.user_models.push_back(load_user_model(f));
    check_model_ids(o.models);
    // select = [...]: built-in ids (variants included) or the model files' ids
    for (const std::string& id : sw.select) {
        bool known = std::any_of(model_registry().begin(), model_registry().end(),
                                 [&](const ModelInfo& m) { return m.id == id; });
        for (const auto& u : o.models.user_models) known |= u->header.id == id;
        if (!known)
            throw StackError(sw.path, sw.select_line,
                             "select: no model '" + id +
                                 "' (gonio models lists the built-in ones; or a models = [...] "
                                 "file's id)");
    }
    o.models.selected = sw.select;
    check_sweep_fits(sw, o.models.user_models);
    const std::string out = a.out.empty() ? "out/sweep-" + safe_file_name(sw.name) : a.out;
    VkContext ctx(a.ctx);
    if (sw.spectral.on && a.bench > 0)
        usage_error("--bench times the RGB sweep's batches; a [spectral] sweep runs one configuration at a time");
    if (sw.spectral.on && a.batch_given)
        usage_error("--batch: a [spectral] sweep traces one configuration at a time (its passes in turn)");
    if (a.bench > 0) return bench_sweep_only(ctx, sw, a, out);
    const uint64_t n = sw.spectral.on ? run_spectral_sweep(ctx, sw, out, o) : run_sweep(ctx, sw, out, o);
    std::printf("sweep %s: %llu configurations computed in shard %llu/%llu (%llu in the sweep) -> %s/configs/\n",
                sw.name.c_str(), (unsigned long long)n, (unsigned long long)o.shard.index,
                (unsigned long long)o.shard.count, (unsigned long long)sw.configurations(), out.c_str());
    if (o.shard.count == 1) {
        uint64_t rows = merge_sweep(out);
        std::printf("wrote %s/sweep.csv (%llu rows) and timings.csv\n", out.c_str(), (unsigned long long)rows);
        run_python_tool("sweep_plot.py", out, "the sweep figures");
    }
    const int rc = check_validation(ctx);
    return std::max(rc, check_finite_json());   // --keep-results: the configurations' summary.json
}

}   // namespace

Command sweep_command() {
    return {"sweep", "SWEEP.toml [options]",
            "vary stack parameters (sweeps/*.toml), run the reference and every model per configuration, and "
            "tabulate their errors in DIR/sweep.csv (figures: atlas.png, sweep.html). A sweep file gives paths per "
            "configuration and angle, or rse = R (each configuration runs as simulate --rse R, paths then the cap); "
            "a [[fit]] block (model, free, start, loss) adds each configuration's best fit of that model as columns "
            "fit.MODEL.KEY, .se, .status and fit.MODEL.loss (docs/SWEEPS.md)",
            "", invocation(&sweep_options, &run_sweep_command)};
}

}   // namespace gonio
