// sweep.h: gonio sweep: vary stack parameters over a grid, run the reference and every model per
// configuration, and tabulate the errors (sweep.csv). Shardable: configuration i belongs to shard i mod N,
// its seed derives from the sweep seed and i, and merging shards gives the bytes of the unsplit run.
#pragma once
#include "model_fit.h"
#include "models.h"
#include "reference.h"
#include "stack.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

// One varied parameter: `key` of layer `layer` (roughness, ior, k, optical_depth, albedo; a scalar applied
// to every channel), or of the stack (layer = -1: exterior_ior), over `values`.
struct SweepAxis {
    int layer = 0;
    std::string key;
    std::vector<double> values;
    int line = 0;   // in the sweep file
};

// One [[fit]]: a model's best fit per configuration (model_fit.h), as gonio fit would find it on the configuration's
// reference; its columns in sweep.csv are fit.MODEL.KEY, fit.MODEL.KEY.se, fit.MODEL.KEY.status per free key and
// fit.MODEL.loss
struct SweepFit {
    FitSpec spec;
    int line = 0;   // in the sweep file
};

struct Sweep {
    std::string name;
    std::string path, text;   // the sweep file and its text
    Stack base;   // the stack it varies
    std::vector<double> theta_i_deg;
    uint64_t paths = 1000000;   // per configuration and incident angle (the cap when rse > 0)
    double rse = 0.0;   // > 0: each configuration and angle runs until its bins above 1% of their
        // slice's peak have this relative standard error (as simulate --rse)
    double rse_quantile = 0.5;   // at this quantile of those bins (SimOptions::rse_quantile)
    uint32_t seed = 1;
    std::vector<SweepAxis> axes;
    std::vector<std::string> model_files;   // models = [...]: users' model files (paths as opened)
    std::vector<SweepFit> fits;   // [[fit]] blocks, one per model
    // select = [ids]: which models run (built-in ids, variants included, and the model files' ids); empty: every
    // built-in model and its variants, and the model files
    std::vector<std::string> select;
    int select_line = 0;
    uint64_t hash = 0;   // of the sweep file's text and the base stack's text: identifies the sweep

    uint64_t configurations() const;
    // The parameter values of configuration i (last axis fastest).
    std::vector<double> values(uint64_t i) const;
    // The stack of configuration i; throws StackError naming the sweep file and the axis if it is invalid.
    Stack stack(uint64_t i) const;
    // The reference seed of configuration i (from the sweep seed and i, never 0).
    uint32_t config_seed(uint64_t i) const;
};

// Parse and validate a sweep file (TOML). Throws StackError (file:line: what was expected).
Sweep parse_sweep_file(const std::string& path);
// Its [[fit]] blocks possible on some configuration, with the sweep's model files read (user_models): the model, the
// keys, the starts. Throws StackError (file:line of the [[fit]]: why not).
void check_sweep_fits(const Sweep& s, const std::vector<std::shared_ptr<const UserModel>>& user_models);

struct ShardSpec {
    uint64_t index = 1, count = 1;
};   // shard k of N, 1-based
ShardSpec parse_shard(const std::string& text);   // "3/64"; throws std::invalid_argument

struct SweepRunOptions {
    ShardSpec shard;
    bool resume = false;   // skip the configurations already written
    bool progress = true;
    ModelOptions models;
    uint32_t batch = 16;   // configurations traced together per dispatch (results do not depend on it)
    bool keep_results = false;   // also write each configuration's slices.csv and summary.json (configs/c-N/)
};

// The walk's specialisation for the whole sweep: specialised when every configuration has the same shape
// (rough and absorbing layers), else the general walk. A property of the sweep, not of a shard or batch, so
// that any sharding traces every configuration with the same code.
bool sweep_specialised(const Sweep& s);

// Configurations per second two ways, in one run, on the first `count` configurations: batched as gonio sweep
// runs them, and one at a time as a loop of gonio compare would (new pipelines each time). Returns sweep-bench.json.
nlohmann::ordered_json bench_sweep(VkContext& ctx, const Sweep& s, uint64_t count, const ModelOptions& models);

// Runs the configurations of one shard into DIR/configs/ (one file each, written atomically); an unsplit run
// (shard 1/1) then merges. Returns the number of configurations computed (not skipped).
uint64_t run_sweep(VkContext& ctx, const Sweep& s, const std::string& dir, const SweepRunOptions& o);

// Gathers DIR/configs/ into DIR/sweep.csv, after checking that every configuration is there, complete and of
// this sweep (else throws std::runtime_error naming what is missing or wrong). Returns the rows written.
uint64_t merge_sweep(const std::string& dir);

}   // namespace gonio
