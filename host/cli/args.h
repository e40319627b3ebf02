// args.h: the command line's options: which command takes which (command_options), their parsing into Args, and
// the refusals (usage_error: the message, then exit 2).
#pragma once
#include "models.h"
#include "reference.h"
#include "vk_context.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gonio {

// What the options of simulate, compare, bench, random-stack, check, models and devices set.
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
    std::vector<std::string> model_files;   // --model FILE (repeatable): read and compiled by load_user_models
    std::string resume;
    uint64_t count = 1;   // random-stack
    uint64_t atlas = 16;   // bench --out: random stacks in the error atlas
    uint64_t atlas_paths = 2000000;
    double checkpoint_seconds = 30.0;   // simulate / compare: the state file written at least this often
    std::string render_env;   // compare --render ENV: the models and the reference on a sphere (OUT/render)
    uint32_t render_size = 0;   // --render-size N (0: the command's default: compare 128, bench 256)
    uint64_t render_paths = 1000000;   // compare --render-paths N: the render's table, paths per angle (0:88:2)
    bool render_paths_given = false;
};

// Which options each command takes (sweep, merge and view parse their own): anything else is refused.
const std::vector<std::pair<std::string, std::vector<std::string>>>& command_options();
// Parses argv[first..] for `cmd`: its own options only; an option of another command, an unknown option or a value
// that cannot work is refused (usage_error).
Args parse_args(const std::string& cmd, int argc, char** argv, int first);

// --models ID,ID,...: the ids, each once (which exist: check_model_ids)
std::vector<std::string> parse_model_ids(const std::string& list);
// The ids --models names exist (built-in, or a --model file's), and no --model file takes an id that is taken.
void check_model_ids(const ModelOptions& o);

// Prints "gonio: MSG" and where the usage is, and exits 2 (a refused command line).
[[noreturn]] void usage_error(const std::string& msg);
// An option's value: a finite number; a whole non-negative number (1e6 is allowed); a comma-separated list of numbers.
double parse_number(const std::string& opt, const std::string& v);
uint64_t parse_count(const std::string& opt, const std::string& v);
std::vector<double> parse_list(const std::string& opt, const std::string& v);

}   // namespace gonio
