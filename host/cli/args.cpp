#include "args.h"
#include "model_registry.h"
#include "user_model.h"
#include "text_format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace gonio {

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
    if (d < 0 || d != std::floor(d) || d > 1.8e19)
        usage_error(opt + ": expected a whole non-negative number, got '" + v + "'");
    return uint64_t(d);
}

// A,B,... where an item A:B:S is the range A, A + S, ... up to B (B itself where S divides B - A)
std::vector<double> parse_list(const std::string& opt, const std::string& v) {
    std::vector<double> out;
    size_t i = 0;
    while (i <= v.size()) {
        size_t j = v.find(',', i);
        if (j == std::string::npos) j = v.size();
        const std::string item = v.substr(i, j - i);
        const size_t c1 = item.find(':');
        if (c1 == std::string::npos) {
            out.push_back(parse_number(opt, item));
        } else {
            const size_t c2 = item.find(':', c1 + 1);
            if (c2 == std::string::npos || item.find(':', c2 + 1) != std::string::npos)
                usage_error(opt + ": a range is FROM:TO:STEP, got '" + item + "'");
            const double a = parse_number(opt, item.substr(0, c1)),
                         b = parse_number(opt, item.substr(c1 + 1, c2 - c1 - 1)),
                         step = parse_number(opt, item.substr(c2 + 1));
            if (!(step > 0) || !(b >= a)) usage_error(opt + ": the range " + item + " needs TO >= FROM and STEP > 0");
            const double n = std::floor((b - a) / step + 1e-9);
            if (n >= 10000) usage_error(opt + ": the range " + item + " has more than 10000 values");
            for (int k = 0; k <= int(n); ++k) out.push_back(std::round((a + k * step) * 1e9) / 1e9);
        }
        i = j + 1;
    }
    return out;
}

const std::vector<std::pair<std::string, std::vector<std::string>>>& command_options() {
    static const std::vector<std::string> walk = {"--theta-i",
                                                  "--paths",
                                                  "--seed",
                                                  "--out",
                                                  "--dtheta",
                                                  "--dphi",
                                                  "--orders",
                                                  "--max-events",
                                                  "--rse",
                                                  "--rse-quantile",
                                                  "--max-seconds",
                                                  "--angles-per-dispatch",
                                                  "--resume",
                                                  "--checkpoint-seconds",
                                                  "--general-walk",
                                                  "--no-series",
                                                  "--no-baked-stack",
                                                  "--device",
                                                  "--validate",
                                                  "--quiet",
                                                  "--invalid-path-for-tests"};
    static const std::vector<std::pair<std::string, std::vector<std::string>>> t = [] {
        std::vector<std::string> simulate = walk, compare = walk;
        simulate.push_back("--cpu-twin");
        compare.insert(compare.end(), {"--no-report", "--no-belcour-tables", "--models", "--model", "--render",
                                       "--render-size", "--render-paths"});
        return std::vector<std::pair<std::string, std::vector<std::string>>>{
            {"simulate", simulate},
            {"compare", compare},
            {"bench",
             {"--theta-i",
              "--paths",
              "--cpu-paths",
              "--seed",
              "--out",
              "--dtheta",
              "--dphi",
              "--max-events",
              "--atlas",
              "--atlas-paths",
              "--no-belcour-tables",
              "--general-walk",
              "--no-series",
              "--no-baked-stack",
              "--device",
              "--validate",
              "--quiet",
              "--model",
              "--models",
              "--render",
              "--render-size"}},
            {"random-stack", {"--seed", "--count", "--out"}},
            {"check", {}},
            {"models", {}},
            {"devices", {}},
        };
    }();
    return t;
}

// --models ID,ID,...: model ids, each once (which exist is checked by check_model_ids, once the --model files are
// read).
std::vector<std::string> parse_model_ids(const std::string& list) {
    std::vector<std::string> ids;
    size_t start = 0;
    while (start <= list.size()) {
        size_t comma = list.find(',', start);
        std::string id = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (id.empty()) usage_error("--models " + list + ": an empty model id (expected ID,ID,...; gonio models)");
        if (std::find(ids.begin(), ids.end(), id) != ids.end()) usage_error("--models: '" + id + "' given twice");
        ids.push_back(id);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return ids;
}

void check_model_ids(const ModelOptions& o) {
    std::vector<std::string> known;
    for (const ModelInfo& m : model_registry()) known.push_back(m.id);
    for (const auto& u : o.user_models) {
        if (std::find(known.begin(), known.end(), u->header.id) != known.end())
            usage_error("--model " + u->header.path + ": the id '" + u->header.id + "' is taken (by another --model " +
                        "file or a built-in model)");
        known.push_back(u->header.id);
    }
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    for (const std::string& id : o.selected)
        if (std::find(known.begin(), known.end(), id) == known.end())
            usage_error("--models: no model '" + id + "' (the models: " + list + ")");
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
                        usage_error("--theta-i: the incident angle " + format_g9(a.sim.theta_i_deg[k]) +
                                    " is given twice");
        } else if (s == "--paths") {
            a.sim.paths = parse_count(s, value());
            a.paths_given = true;
        } else if (s == "--cpu-paths")
            a.cpu_paths = parse_count(s, value());
        else if (s == "--seed") {
            uint64_t v = parse_count(s, value());
            if (v > 0xffffffffull) usage_error("--seed must fit in 32 bits");
            a.sim.seed = uint32_t(v);
        } else if (s == "--out")
            a.out = value();
        else if (s == "--dtheta")
            a.sim.dtheta_deg = parse_number(s, value());
        else if (s == "--dphi")
            a.sim.dphi_deg = parse_number(s, value());
        else if (s == "--orders")
            a.sim.orders = true;
        else if (s == "--max-events") {
            uint64_t v = parse_count(s, value());
            if (v > 1000000) usage_error("--max-events too large");
            a.sim.max_events = uint32_t(v);
        } else if (s == "--cpu-twin")
            a.cpu_twin = true;
        else if (s == "--rse") {
            a.sim.rse_target = parse_number(s, value());
            if (!(a.sim.rse_target > 0 && a.sim.rse_target < 1)) usage_error("--rse must be in (0, 1), e.g. 0.01");
        } else if (s == "--rse-quantile") {
            a.sim.rse_quantile = parse_number(s, value());
            if (!(a.sim.rse_quantile > 0 && a.sim.rse_quantile <= 1))
                usage_error("--rse-quantile must be in (0, 1], e.g. 0.5 (the median) or 1 (the worst bin)");
        } else if (s == "--checkpoint-seconds") {
            a.checkpoint_seconds = parse_number(s, value());
            if (!(a.checkpoint_seconds >= 0))
                usage_error("--checkpoint-seconds must be at least 0 (0: no checkpoints)");
        } else if (s == "--angles-per-dispatch") {
            uint64_t v = parse_count(s, value());
            if (v > 65535) usage_error("--angles-per-dispatch: at most 65535 (workgroup rows of one dispatch)");
            a.sim.angles_per_dispatch = uint32_t(v);
        } else if (s == "--max-seconds") {
            a.sim.max_seconds = parse_number(s, value());
            if (!(a.sim.max_seconds > 0)) usage_error("--max-seconds must be positive");
        } else if (s == "--resume")
            a.resume = value();
        else if (s == "--count")
            a.count = parse_count(s, value());
        else if (s == "--atlas")
            a.atlas = parse_count(s, value());
        else if (s == "--atlas-paths")
            a.atlas_paths = parse_count(s, value());
        else if (s == "--no-report")
            a.no_report = true;
        else if (s == "--render") {
            a.render_env = value();
            if (a.render_env.empty())
                usage_error("--render needs an environment (furnace, studio, a map's name, FILE.exr)");
        } else if (s == "--render-size") {
            const uint64_t v = parse_count(s, value());
            if (v < 8 || v > 2048) usage_error("--render-size must be 8 to 2048 pixels, got " + std::to_string(v));
            a.render_size = uint32_t(v);
        } else if (s == "--render-paths") {
            a.render_paths = parse_count(s, value());
            a.render_paths_given = true;
            if (a.render_paths < 2) usage_error("--render-paths: at least 2 per angle (two halves)");
        } else if (s == "--no-belcour-tables")
            a.models.belcour_tables = false;
        else if (s == "--models")
            a.models.selected = parse_model_ids(value());
        else if (s == "--model")
            a.model_files.push_back(value());
        else if (s == "--general-walk")
            a.sim.specialised = false;
        else if (s == "--no-series")
            a.sim.series = false;
        else if (s == "--no-baked-stack")
            a.sim.baked_stack = false;
        else if (s == "--device")
            a.ctx.device_index = int(parse_count(s, value()));
        else if (s == "--validate")
            a.ctx.validation = true;
        else if (s == "--quiet")
            a.sim.progress = false;
        else if (s == "--invalid-path-for-tests") {   // undocumented: gonio's tests of the invalid class
            uint64_t v = parse_count(s, value());
            if (v >= 0xffffffffull) usage_error("--invalid-path-for-tests: a path index below 2^32 - 1");
            a.sim.invalid_path_for_tests = uint32_t(v);
        } else if (s.rfind("--", 0) == 0)
            usage_error("unknown option " + s);
        else
            a.positional.push_back(s);
    }
    if (a.render_env.empty() && (a.render_size != 0 || a.render_paths_given))
        usage_error("--render-size and --render-paths set up --render ENV, which is not given");
    // without --model files the ids --models names are known now (else once the files are read: load_user_models)
    if (a.model_files.empty()) check_model_ids(a.models);
    return a;
}

}   // namespace gonio
