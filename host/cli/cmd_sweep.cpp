#include "cmd_sweep.h"
#include "args.h"
#include "json.h"
#include "output.h"
#include "python_tool.h"
#include "sweep.h"
#include "user_model.h"
#include "validation.h"
#include "vk_context.h"

#include <cstdio>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace gonio {

// Its own options (--resume takes no value here).
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
        if (a == "--out")
            out = value();
        else if (a == "--shard") {
            try {
                o.shard = parse_shard(value());
            } catch (const std::invalid_argument& e) { usage_error(e.what()); }
        } else if (a == "--resume")
            o.resume = true;
        else if (a == "--keep-results")
            o.keep_results = true;
        else if (a == "--quiet")
            o.progress = false;
        else if (a == "--device")
            ctx_opt.device_index = int(parse_count(a, value()));
        else if (a == "--validate")
            ctx_opt.validation = true;
        else if (a == "--no-belcour-tables")
            o.models.belcour_tables = false;
        else if (a == "--batch") {
            uint64_t v = parse_count(a, value());
            if (v < 1 || v > 4096) usage_error("--batch must be in [1, 4096]");
            o.batch = uint32_t(v);
        } else if (a == "--bench")
            bench = parse_count(a, value());
        else if (a.rfind("--", 0) == 0)
            usage_error("unknown option " + a + " for sweep");
        else if (file.empty())
            file = a;
        else
            usage_error("sweep takes one sweep file");
    }
    if (file.empty()) usage_error("sweep: no sweep file (see sweeps/*.toml)");
    Sweep sw = parse_sweep_file(file);
    // the sweep's model files, compiled before any configuration runs (a compile error: FILE:LINE, exit 2)
    for (const std::string& f : sw.model_files) o.models.user_models.push_back(load_user_model(f));
    check_model_ids(o.models);
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
    std::printf("sweep %s: %llu configurations computed in shard %llu/%llu (%llu in the sweep) -> %s/configs/\n",
                sw.name.c_str(), (unsigned long long)n, (unsigned long long)o.shard.index,
                (unsigned long long)o.shard.count, (unsigned long long)sw.configurations(), out.c_str());
    if (o.shard.count == 1) {
        uint64_t rows = merge_sweep(out);
        std::printf("wrote %s/sweep.csv (%llu rows) and timings.csv\n", out.c_str(), (unsigned long long)rows);
        run_python_tool("sweep_plot.py", out, "the sweep figures");
    }
    int rc = check_validation(ctx);
    if (non_finite_json_numbers() > 0) {   // --keep-results: the configurations' summary.json
        std::fprintf(stderr,
                     "gonio: %llu numbers of summary.json were not finite (written as null): a bug, please report it\n",
                     (unsigned long long)non_finite_json_numbers());
        rc = 1;
    }
    return rc;
}

// It takes no options.
int cmd_merge(int argc, char** argv) {
    for (int i = 2; i < argc; ++i)
        if (std::string(argv[i]).rfind("--", 0) == 0)
            usage_error("unknown option " + std::string(argv[i]) + " for merge (it takes no options)");
    if (argc != 3) usage_error("merge takes one sweep output directory");
    uint64_t rows = merge_sweep(argv[2]);
    std::printf("wrote %s/sweep.csv (%llu rows) and timings.csv\n", argv[2], (unsigned long long)rows);
    run_python_tool("sweep_plot.py", argv[2], "the sweep figures");
    return 0;
}

}   // namespace gonio
