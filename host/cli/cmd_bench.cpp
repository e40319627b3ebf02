// cmd_bench.cpp: `gonio bench`: its options, and the measurements (bench.h).
#include "cmd_bench.h"
#include "bench.h"
#include "common_options.h"
#include "spectral_bench.h"

namespace gonio {

namespace {

constexpr const char* kBenchNotes =
    R"(bench prints, per stack, paths per second of the stack-specialised walk, of the general N-layer walk, and of
the CPU twin (same shader sources, all cores), measured in one run, with their ratios, and the mean events per
path (interface events and collisions in scattering media; 2^16 paths of the CPU twin).
With --out DIR it also measures, per stack, the reference's convergence (relative RMS error against a 2^25-path
run and median relative standard error, against paths and seconds, with the 1/sqrt(N) fit and the seconds to
reach 1% and 0.1%), and every model on the 2^25-path run's bins (device seconds per evaluation and per grid
against its RMSE in log(1 + sqrt f)); then the error atlas: --atlas K random two-layer stacks (a coat over a
conductor), the reference (--atlas-paths per angle) and every model at 0/30/60/80 degrees, the best model per
stack and angle. Writes DIR/bench.json, convergence.png, pareto.png, atlas.png and bench.html
(tools/bench_plot.py).
)";

struct BenchSettings {
    WalkSettings walk;
    uint64_t cpu_paths = 1000000;
    uint64_t atlas = 16;   // --out: random stacks in the error atlas
    uint64_t atlas_paths = 2000000;
    ModelSettings models;
    RenderAlong render;
    bool spectral = false, bands_given = false;
    SpectralBands bands;
};

OptionTable bench_options(BenchSettings& a) {
    const OptionTable walk = walk_options(a.walk), models = model_options(a.models),
                      render = render_along_options(a.render);
    const OptionTable own = {
        retold(walk, "--theta-i", "the one incident angle, degrees (default 0)"),
        retold(walk, "--paths", "device paths per throughput run (default 2e7)"),
        {"--cpu-paths", "N", "CPU twin paths per throughput run (default 1e6)",
         [&a](const std::string& v) { a.cpu_paths = parse_count("--cpu-paths", v); }},
        retold(walk, "--seed", "seed of the runs and of the atlas's random stacks (default 1)"),
        retold(walk, "--out",
               "also measure convergence, the models' cost against their error and the error atlas, into DIR (see "
               "below; default: the throughput table only)"),
        {"--atlas", "K", "random two-layer stacks in the error atlas of --out, at most 10000 (default 16, 0: none)",
         [&a](const std::string& v) { a.atlas = parse_count("--atlas", v); }},
        {"--atlas-paths", "N", "reference paths per incident angle of an atlas stack, at least 1 (default 2e6)",
         [&a](const std::string& v) { a.atlas_paths = parse_count("--atlas-paths", v); }},
        {"--spectral", nullptr,
         "instead: per stack (default: stacks/coats/coated-gold.toml and tinted-coat-copper.toml), a spectral run "
         "(10 nm bands, paths shared by weight) and an RGB run of --paths (default 2e6), each run's seconds to a 1% "
         "median rse in X, Y and Z, and the spectral run's cost at equal error (docs/SPECTRAL.md)",
         [&a](const std::string&) { a.spectral = true; }},
    };
    const OptionTable shared =
        pick_options(walk, {"--dtheta", "--dphi", "--max-events", "--general-walk", "--no-series", "--no-branching",
                            "--no-baked-stack", "--device", "--validate", "--quiet"});
    const OptionTable rendered = {
        retold(render, "--render",
               "also time gonio render's stages per stack under ENV (as render --env; a 1024 x 512 map such as "
               "forest): the 0:88:2 table in two halves, the reference's sum on the CPU, every model that represents "
               "the stack on the device (64 iterations each)"),
        retold(render, "--render-size", "the rendering's pixels across, 8 to 2048 (default 256)"),
    };
    return own + shared + models + rendered + spectral_band_options(a.bands, a.bands_given, "--spectral");
}

int run_bench_command(BenchSettings& a, const std::vector<std::string>& operands) {
    check_render_along(a.render);
    if (a.bands_given && !a.spectral) usage_error("--bands and --band-paths go with --spectral");
    if (a.spectral) {
        if (!a.walk.out.empty() || !a.render.env.empty())
            usage_error("bench --spectral prints its table only (no --out, no --render)");
        if (a.walk.sim.theta_i_deg.size() != 1) usage_error("bench takes one --theta-i");
        SimOptions sim = a.walk.sim;
        if (!a.walk.paths_given) sim.paths = 2000000;
        const std::vector<std::string> stacks =
            operands.empty()
                ? std::vector<std::string>{"stacks/coats/coated-gold.toml", "stacks/coats/tinted-coat-copper.toml"}
                : operands;
        return run_spectral_bench(stacks, sim, a.walk.ctx, a.bands);
    }
    BenchOptions b;
    b.stacks = operands;
    b.sim = a.walk.sim;
    if (!a.walk.paths_given) b.sim.paths = 20000000;
    b.cpu_paths = a.cpu_paths;
    b.ctx = a.walk.ctx;
    load_model_files(a.models, false);
    b.models = a.models.models;
    b.out = a.walk.out;
    if (a.atlas > 10000) usage_error("--atlas: at most 10000 stacks");
    b.atlas_stacks = uint32_t(a.atlas);
    if (a.atlas_paths < 1) usage_error("--atlas-paths must be at least 1");
    b.atlas_paths = a.atlas_paths;
    if (b.sim.theta_i_deg.size() != 1) usage_error("bench takes one --theta-i");
    b.render_env = a.render.env;
    if (a.render.size) b.render_size = a.render.size;
    return run_bench(b);
}

}   // namespace

Command bench_command() {
    return {"bench", "[STACK.toml ...] [options]",
            "paths per second per stack on the device and on the CPU twin (default: every stacks/*.toml); --out DIR "
            "adds convergence, the models' cost against their error, and an error atlas",
            kBenchNotes, invocation(&bench_options, &run_bench_command)};
}

}   // namespace gonio
