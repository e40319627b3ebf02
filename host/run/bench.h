// bench.h: what gonio bench measures: paths per second of the reference (device, general walk, CPU twin), incident
// angles side by side against one at a time, and with an output directory the reference's convergence, what each
// model costs against how far it is from the reference (Pareto), an error atlas over random two-layer stacks, and
// the render's stages.
#pragma once
#include "model_registry.h"
#include "sim_options.h"
#include "vk_context.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

struct BenchOptions {
    std::vector<std::string> stacks;   // stack files; empty: every stacks/*.toml
    SimOptions sim;   // one incident angle; paths: device paths per throughput run
    uint64_t cpu_paths = 1000000;   // CPU twin paths
    ContextOptions ctx;
    ModelOptions models;
    std::string out;   // "": throughput table only; else bench.json, figures, bench.html there
    uint32_t atlas_stacks = 16;   // with out: random two-layer stacks in the error atlas (0: none)
    uint64_t atlas_paths = 2000000;   // reference paths per incident angle of an atlas stack
    std::string render_env;   // --render ENV: also time gonio render's stages per stack ("": not)
    uint32_t render_size = 256;
};

// Prints the throughput table; with `out`, also measures the reference's convergence, the models' cost and
// error (Pareto), the error atlas, and writes DIR/bench.json, the figures and DIR/bench.html. Returns the
// process exit status (3 if the validation layer reported anything).
int run_bench(const BenchOptions& b);

}   // namespace gonio
