// sweep.h: gonio sweep: vary stack parameters over a grid, run the reference and every model per
// configuration, and tabulate the errors (sweep.csv). Shardable: configuration i belongs to shard i mod N,
// its seed derives from the sweep seed and i, and merging shards gives the bytes of the unsplit run.
#pragma once
#include "measured_materials.h"
#include "model_fit.h"
#include "models.h"
#include "reference.h"
#include "spectral_bands.h"
#include "stack.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

// One varied parameter: `key` of layer `layer` (a layer key of the vocabulary, stack_vocabulary.h: layer_key_names; a
// scalar applied to every channel), or of the stack (layer = -1: exterior_ior), over `values`.
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

// [spectral]: each configuration traced band by band (compare --spectral), its models' colour errors and its RGB run's
// (its measured materials reduced by `reduction`) in sweep.csv instead of the RGB errors (docs/SWEEPS.md)
struct SweepSpectral {
    bool on = false;
    SpectralBands bands;
    RgbReduction reduction = RgbReduction::Dominant;
    int line = 0;   // in the sweep file
};

// A spectral sweep's columns after the configuration's values: per configuration, angle, side and model (the
// models, the stack's RGB run as "rgb-run", the reference as "reference" with the colour fields empty) how it was
// evaluated (band-by-band, or rgb-reduced-R: on the stack reduced to RGB by reduction R), the albedo in XYZ (model and reference), its CIEDE2000 and Delta E_ITP, and over the lit bins the
// colour differences and their noise floor (colour_error.h)
constexpr const char* kSpectralSweepColumns =
    "theta_i,side,model,evaluated,albedo_x_model,albedo_y_model,albedo_z_model,albedo_x_reference,"
    "albedo_y_reference,albedo_z_reference,albedo_de2000,albedo_de_itp,lit_bins,median_de2000,p95_de2000,max_de2000,"
    "median_de_itp,p95_de_itp,noise_de2000,reference_paths";

struct Sweep {
    std::string name;
    std::string path, text;   // the sweep file and its text
    Stack base;   // the stack it varies
    std::vector<double> theta_i_deg;
    double phi_i_deg = 0.0;   // the incident azimuth of every angle (phi_i = DEG), degrees in [0, 360)
    uint64_t paths = 1000000;   // per configuration and incident angle (the cap when rse > 0)
    double rse = 0.0;   // > 0: each configuration and angle runs until its bins above 1% of their
        // slice's peak have this relative standard error (as simulate --rse)
    double rse_quantile = 0.5;   // at this quantile of those bins (SimOptions::rse_quantile)
    uint32_t seed = 1;
    uint32_t max_events = 256;   // max_events = N: the walk's event cap per path (SimOptions::max_events)
    std::vector<SweepAxis> axes;
    std::vector<std::string> model_files;   // models = [...]: users' model files (paths as opened)
    std::vector<SweepFit> fits;   // [[fit]] blocks, one per model
    // select = [ids]: which models run (built-in ids, variants included, and the model files' ids); empty: every
    // built-in model and its variants, and the model files
    std::vector<std::string> select;
    int select_line = 0;
    SweepSpectral spectral;
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

// The pieces a sweep's run is made of (run_sweep's, and a spectral sweep's: host/cli/spectral_sweep.h).
// The configurations of o.shard that DIR/configs/ does not hold complete (DIR/sweep.json written, or checked to be
// this sweep's; a configuration already there without --resume, or a file of something else, refused); `mine`: the
// shard's configurations in all.
std::vector<uint64_t> sweep_todo(const Sweep& s, const std::string& dir, const SweepRunOptions& o, uint64_t& mine);
// The walk's options of every configuration: the sweep's angles, paths and rse, no progress line.
SimOptions sweep_sim_options(const Sweep& s, bool specialised);
// "I,V1,V2,...": configuration i's first columns (its number and its values)
std::string config_prefix(const Sweep& s, uint64_t i);
// Configuration i's rows as its file (its first and end lines added, which mark it complete), written atomically,
// and its seconds beside it.
void write_config(const Sweep& s, const std::string& dir, uint64_t i, const std::string& rows, double seconds);
// DIR/configs/c-N: where --keep-results writes configuration i's files
std::string config_result_dir(const std::string& dir, uint64_t i);
// The progress line: done of the shard's `mine`, and the time left for `left` at the pace of `computed`.
void print_sweep_progress(const Sweep& s, const SweepRunOptions& o, uint64_t done, uint64_t mine, uint64_t computed,
                          uint64_t left, double elapsed_seconds);

// Gathers DIR/configs/ into DIR/sweep.csv, after checking that every configuration is there, complete and of
// this sweep (else throws std::runtime_error naming what is missing or wrong). Returns the rows written.
uint64_t merge_sweep(const std::string& dir);

}   // namespace gonio
