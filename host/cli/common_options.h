// common_options.h: the options that several commands share, each written once: the walk's (simulate, compare and
// some of them bench), the models' (compare, bench, render), compare's and bench's --render, and the device's.
#pragma once
#include "spectral_bands.h"
#include "model_registry.h"
#include "options.h"
#include "sim_options.h"
#include "vk_context.h"

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace gonio {

// What the walk's options set: a reference run of simulate or compare.
struct WalkSettings {
    SimOptions sim;   // its progress line on unless --quiet
    ContextOptions ctx;
    std::string out;   // --out DIR ("": the command's default)
    std::string resume;   // --resume DIR
    bool paths_given = false;
    std::set<std::string> given;   // the options on the command line (--resume takes the others from the state)
    double checkpoint_seconds = 30.0;   // the state file written at least this often (0: at the end only)
    WalkSettings() { sim.progress = true; }
};
// The options of a reference run, as simulate and compare take them (bench takes some of them: pick_options).
OptionTable walk_options(WalkSettings& w);

// What the models' options set.
struct ModelSettings {
    ModelOptions models = published_models();   // the commands' default: no variants (--models all adds them)
    static ModelOptions published_models() {
        ModelOptions o;
        o.variants = false;
        return o;
    }
    std::vector<std::string> files;   // --model FILE (repeatable): read and compiled by load_model_files
};
// --no-belcour-tables, --models ID,ID,..., --model FILE, as compare takes them.
OptionTable model_options(ModelSettings& m);
// Reads and compiles the --model files into m.models (a broken file: FILE:LINE, exit 2; with `progress` each file's
// compile time on stderr), then checks the ids --models names (check_model_ids).
void load_model_files(ModelSettings& m, bool progress);
// --models ID,ID,...: the ids, each once (which exist: check_model_ids)
std::vector<std::string> parse_model_ids(const std::string& list);
// The ids --models names exist (built-in, or a --model file's), and no --model file takes an id that is taken.
void check_model_ids(const ModelOptions& o);

// What --render, --render-size and --render-paths set: a render beside compare's run, or timed by bench.
struct RenderAlong {
    std::string env;   // "": no render
    uint32_t size = 0;   // 0: the command's default
    uint64_t paths = 1000000;   // the render's table, paths per angle
    bool paths_given = false;
};
// --render ENV, --render-size N and --render-paths N, as compare takes them.
OptionTable render_along_options(RenderAlong& r);

// --bands W and --band-paths even|weight, the bands of a spectral run (docs/SPECTRAL.md); `with` names the option they
// go with in the help ("--spectral"), `given` is set when either is given.
OptionTable spectral_band_options(SpectralBands& b, bool& given, const std::string& with);
// --render-size or --render-paths without --render ENV: refused.
void check_render_along(const RenderAlong& r);

// --device I, --validate, and --seed S (its help says what the seed picks).
Option device_option(ContextOptions& c);
Option validate_option(ContextOptions& c);
Option seed_option(uint32_t& seed, const std::string& help);

// The options of `from` named in `names`, in that order.
OptionTable pick_options(const OptionTable& from, const std::vector<std::string>& names);
// The option of `from` named `name` with its own help (for a command where its default or its use differs).
Option retold(const OptionTable& from, const std::string& name, const std::string& help);
// a's options, then b's.
OptionTable operator+(OptionTable a, const OptionTable& b);

}   // namespace gonio
