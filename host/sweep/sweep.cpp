// gonio sweep and merge: see sweep.h and docs/SWEEPS.md.
#include "sweep.h"
#include "input_file.h"
#include "stack_spectral.h"
#include "text_format.h"
#include "json.h"
#include "comparison.h"
#include "crc32c.h"
#include "models_json.h"
#include "output.h"
#include "stack_gpu.h"
#include "stack_vocabulary.h"
#include "vk_context.h"

#include <toml++/toml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace gonio {

namespace {

uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return h;
}

std::string hex(uint64_t v) {
    char b[24];
    std::snprintf(b, sizeof b, "%016llx", (unsigned long long)v);
    return b;
}

std::string num(double v) { return format_g9(v); }

std::string column_name(const SweepAxis& a) {
    return a.layer < 0 ? a.key : "layer" + std::to_string(a.layer + 1) + "." + a.key;   // layers numbered from 1
}

std::string read_text(const std::string& path) { return read_input_file(path, "sweep file"); }

}   // namespace

uint64_t Sweep::configurations() const {
    uint64_t n = 1;
    for (auto& a : axes) n *= a.values.size();
    return n;
}

std::vector<double> Sweep::values(uint64_t i) const {
    std::vector<double> v(axes.size());
    for (size_t k = axes.size(); k-- > 0;) {
        uint64_t n = axes[k].values.size();
        v[k] = axes[k].values[i % n];
        i /= n;
    }
    return v;
}

Stack Sweep::stack(uint64_t i) const {
    Stack s = base;
    s.name = base.name + "-" + std::to_string(i);
    std::vector<double> v = values(i);
    for (size_t k = 0; k < axes.size(); ++k) {
        const SweepAxis& a = axes[k];
        float x = float(v[k]);
        if (a.layer < 0) {
            s.*find_stack_key(a.key)->value = x;
            continue;
        }
        Layer& L = s.layers.at(size_t(a.layer));
        find_layer_key(L.kind, a.key)->set(L, glm::vec3(x));   // parse_sweep_file: a key of the layer's kind
    }
    try {
        validate_stack(s);
    } catch (const StackError& e) {
        std::string what = e.what();
        throw StackError(path, axes.empty() ? 0 : axes[0].line,
                         "configuration " + std::to_string(i) + " makes an invalid stack: " + what);
    }
    s.source_text = stack_to_toml(s);
    return s;
}

uint32_t Sweep::config_seed(uint64_t i) const {
    // splitmix64 of (seed, i): independent streams per configuration, the same whatever the sharding
    uint64_t z = (uint64_t(seed) << 32) ^ (i + 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    uint32_t s32 = uint32_t(z ^ (z >> 32));
    return s32 ? s32 : 1u;
}

namespace {

// A sweep file, read part by part; every refusal names the file and line.
struct SweepParser {
    Sweep& s;
    static int line_of(const toml::node& n) { return int(n.source().begin.line); }
    [[noreturn]] void fail(int line, const std::string& m) const { throw StackError(s.path, line, m); }
    fs::path beside(const std::string& f) const {   // a path relative to the sweep file
        return fs::path(f).is_absolute() ? fs::path(f) : fs::path(s.path).parent_path() / f;
    }

    void top_keys(const toml::table& t) const {
        const std::set<std::string> top = {"name", "stack", "theta_i", "phi_i",  "paths", "rse",      "rse_quantile",
                                           "seed", "vary",  "models",  "select", "fit",   "spectral", "max_events"};
        for (auto& [k, v] : t)
            if (!top.count(std::string(k.str())))
                fail(line_of(v),
                     "unknown key '" + std::string(k.str()) +
                         "' (expected name, stack, theta_i, phi_i, paths, rse, rse_quantile, seed, max_events, "
                         "models, select, [[vary]], [[fit]], [spectral])");
    }

    // [spectral]: bands, band_points, band_paths, reduction, as compare --spectral takes them (docs/SWEEPS.md); every
    // configuration must be traceable band by band
    void spectral(const toml::table& t) const {
        const toml::node* node = t.get("spectral");
        if (!node) return;
        const int line = line_of(*node);
        const toml::table* sp = node->as_table();
        if (!sp) fail(line, "spectral: expected a table [spectral] (bands, band_points, band_paths, reduction)");
        SweepSpectral& o = s.spectral;
        o.on = true;
        o.line = line;
        for (auto& [k, x] : *sp) {
            const std::string key(k.str());
            const int at = line_of(x);
            if (key == "bands") {
                o.bands.width_nm = x.value<double>().value_or(NAN);
            } else if (key == "band_points") {
                const std::optional<int64_t> v = x.value<int64_t>();
                if (!v || *v < 1 || *v > int64_t(SpectralBands::kMaxPoints))
                    fail(at,
                         "band_points: expected a whole number from 1 to " + std::to_string(SpectralBands::kMaxPoints));
                o.bands.points = unsigned(*v);
            } else if (key == "band_paths") {
                try {
                    o.bands.pass_paths = parse_pass_paths(x.value<std::string>().value_or(""));
                    o.bands.pass_paths_chosen = true;
                } catch (const std::invalid_argument& e) { fail(at, std::string("band_paths: ") + e.what()); }
            } else if (key == "reduction") {
                try {
                    o.reduction = parse_rgb_reduction(x.value<std::string>().value_or(""));
                } catch (const std::invalid_argument& e) { fail(at, std::string("reduction: ") + e.what()); }
            } else {
                fail(at,
                     "unknown key '" + key + "' in [spectral] (expected bands, band_points, band_paths, reduction)");
            }
        }
        try {
            o.bands.check();
        } catch (const std::invalid_argument& e) { fail(line, std::string("[spectral] bands: ") + e.what()); }
        if (pass_paths_for(o.bands, s.rse) == SpectralBands::PassPaths::Measured && s.rse > 0)
            fail(line,
                 "[spectral] band_paths = \"measured\" shares paths between the passes; with rse each pass runs "
                 "to its own error: give one or the other");
        const double first = o.bands.point_nm(0, 0), last = o.bands.point_nm(o.bands.count() - 1, o.bands.points - 1);
        for (uint64_t i = 0; i < s.configurations(); ++i)
            if (const std::string why = spectral_refusal(s.stack(i), first, last); !why.empty())
                fail(line, "[spectral]: configuration " + std::to_string(i) + " cannot be traced band by band: " + why);
    }

    // models = ["my_coat.glsl", ...]: users' model files (docs/MODELS.md "Your own model"), relative to the sweep
    // file, run beside the built-in ones; returns their text, which is part of the sweep's hash
    std::string model_files(const toml::table& t) const {
        std::string texts;
        auto* node = t.get("models");
        if (!node) return texts;
        auto* arr = node->as_array();
        if (!arr) fail(line_of(*node), "models: expected a list of model files, e.g. models = [\"my_coat.glsl\"]");
        for (auto& e : *arr) {
            auto f = e.value<std::string>();
            if (!f || f->empty()) fail(line_of(e), "models: expected file names (strings)");
            const fs::path mp = beside(*f);
            const std::string why = input_file_refusal(mp.string(), "model file", kMaxTextFileBytes);
            if (!why.empty()) fail(line_of(e), "models: " + mp.string() + ": " + why);
            texts += read_input_file(mp.string(), "model file");
            s.model_files.push_back(mp.string());
        }
        return texts;
    }

    // select = ["ID", "ID+VARIANT", ...]: which models run (the ids are checked once the model files are
    // read: cmd_sweep)
    void selected_models(const toml::table& t) const {
        auto node = t["select"];
        if (!node) return;
        s.select_line = line_of(*node.node());
        auto* arr = node.as_array();
        if (!arr || arr->empty())
            fail(s.select_line,
                 "select: expected a list of model ids, select = [\"ID\", \"ID+VARIANT\", ...] (gonio models lists "
                 "them)");
        for (auto& e : *arr) {
            auto id = e.value<std::string>();
            if (!id || id->empty()) fail(line_of(e), "select: expected model ids (strings)");
            if (std::find(s.select.begin(), s.select.end(), *id) != s.select.end())
                fail(line_of(e), "select: '" + *id + "' given twice");
            s.select.push_back(*id);
        }
    }

    // theta_i, phi_i, rse, rse_quantile, paths, seed
    void run_options(const toml::table& t) const {
        if (auto p = t["phi_i"]) {
            auto v = p.value<double>();
            if (!v || !(*v >= 0 && *v < 360))
                fail(line_of(*p.node()), "phi_i: expected the incident azimuth in degrees in [0, 360)");
            if (*v != 0 && t.contains("spectral"))
                fail(line_of(*p.node()), "phi_i: a [spectral] sweep traces the plane of incidence (phi_i 0)");
            s.phi_i_deg = *v;
        }
        if (auto* arr = t["theta_i"].as_array()) {
            for (auto& e : *arr) {
                auto v = e.value<double>();
                if (!v || !(*v >= 0 && *v < 90)) fail(line_of(e), "theta_i: expected angles in degrees in [0, 90)");
                s.theta_i_deg.push_back(*v);
            }
            if (s.theta_i_deg.empty()) fail(line_of(*arr), "theta_i: expected at least one angle");
        } else {
            fail(1, "missing theta_i = [angles in degrees]");
        }
        if (auto p = t["rse"]) {
            auto v = p.value<double>();
            if (!v || !(*v > 0 && *v < 1))
                fail(line_of(*p.node()), "rse: expected a relative standard error in (0, 1), e.g. 0.01");
            s.rse = *v;
            s.paths = 100000000;   // the default cap with rse
        }
        if (auto p = t["rse_quantile"]) {
            auto v = p.value<double>();
            if (!v || !(*v > 0 && *v <= 1))
                fail(line_of(*p.node()), "rse_quantile: expected a quantile in (0, 1], e.g. 0.5 (the median)");
            if (!(s.rse > 0)) fail(line_of(*p.node()), "rse_quantile: only with rse = R");
            s.rse_quantile = *v;
        }
        if (auto p = t["paths"]) {
            auto v = p.value<double>();
            if (!v || !(*v >= 1 && *v <= 1e12) || std::floor(*v) != *v)
                fail(line_of(*p.node()), "paths: expected a whole number in [1, 1e12]");
            s.paths = uint64_t(*v);
        }
        if (auto p = t["seed"]) {
            auto v = p.value<int64_t>();
            if (!v || *v < 0 || *v > 0xffffffffll) fail(line_of(*p.node()), "seed: expected an integer in [0, 2^32)");
            s.seed = uint32_t(*v);
        }
        if (auto p = t["max_events"]) {   // as simulate --max-events
            auto v = p.value<int64_t>();
            if (!v || *v < 1 || *v > 1000000)
                fail(line_of(*p.node()), "max_events: expected an event cap per path, an integer in [1, 1e6]");
            s.max_events = uint32_t(*v);
        }
    }

    // "roughness, ior, ..., exterior_ior": the keys a [[vary]] may name (stack_vocabulary.h)
    static std::string varied_keys() {
        std::string list;
        for (const std::string& k : layer_key_names()) list += k + ", ";
        for (const StackKey& k : stack_keys()) list += std::string(k.name) + ", ";
        return list.substr(0, list.size() - 2);
    }

    static std::string axis_name(const SweepAxis& a) {
        return a.layer < 0 ? a.key : "layer " + std::to_string(a.layer + 1) + "'s " + a.key;
    }
    std::string range_text(const SweepAxis& a) const {
        return a.layer < 0 ? find_stack_key(a.key)->range_text()
                           : find_layer_key(s.base.layers[size_t(a.layer)].kind, a.key)->range_text();
    }

    // which parameter a [[vary]] varies: a key of the stack (layer -1) or of one layer of the kind that takes it
    void varied_parameter(const toml::table& v, SweepAxis& a, int line) const {
        auto key = v["key"].value<std::string>();
        if (!key) fail(line, "[[vary]]: missing key = \"roughness\" (one of " + varied_keys() + ")");
        a.key = *key;
        if (find_stack_key(a.key)) {
            a.layer = -1;
            return;
        }
        const auto named = named_keys();
        const bool is_named =
            std::any_of(named.begin(), named.end(), [&](const NamedKey& n) { return a.key == n.name; });
        if (const ChoiceKey* c = find_choice_key(a.key); c || is_named)
            fail(line, "[[vary]]: '" + a.key + "' takes a word" + (c ? " (" + c->words_text() + ")" : std::string()) +
                           ", and a sweep varies numbers (one of " + varied_keys() +
                           "): set it in the stack file, a sweep for each word");
        if (!is_layer_key(a.key))
            fail(line, "[[vary]]: unknown key '" + a.key + "' (expected one of " + varied_keys() + ")");
        // layers are numbered from 1, top to bottom, as in `gonio check`, error messages and the viewer
        auto layer = v["layer"].value<int64_t>();
        if (!layer || *layer < 1 || *layer > int64_t(s.base.layers.size()))
            fail(line, "[[vary]]: layer must be the number of one of the stack's layers (1 to " +
                           std::to_string(s.base.layers.size()) + ", top to bottom)");
        a.layer = int(*layer - 1);
        const InterfaceKind kind = s.base.layers[size_t(a.layer)].kind;
        if (!layer_key_applies(kind, a.key))
            fail(line, "[[vary]]: key '" + a.key + "' does not apply to layer " + std::to_string(*layer) + ", a " +
                           to_string(kind) + " interface (as in a stack file)");
    }

    // the values of a [[vary]]: values = [...], or linear / log / random = {from, to, count[, log]}
    void axis_values(const toml::table& v, SweepAxis& a, int line) const {
        int forms = int(bool(v["values"])) + int(bool(v["linear"])) + int(bool(v["log"])) + int(bool(v["random"]));
        if (forms != 1)
            fail(line,
                 "[[vary]]: give exactly one of values = [...], linear = {from, to, count}, log = {...}, random = "
                 "{from, to, count, log}");
        if (auto* arr = v["values"].as_array()) {
            for (auto& e : *arr) {
                auto x = e.value<double>();
                if (!x) fail(line_of(e), "values: expected numbers");
                a.values.push_back(*x);
            }
            return;
        }
        std::string form = v["linear"] ? "linear" : v["log"] ? "log" : "random";
        auto* r = v[form].as_table();
        if (!r) fail(line, form + " must be an inline table {from = ..., to = ..., count = ...}");
        auto from = (*r)["from"].value<double>(), to = (*r)["to"].value<double>();
        auto count = (*r)["count"].value<int64_t>();
        if (!from || !to || !count || *count < 1 || *count > 100000)
            fail(line, form + ": expected from, to (numbers) and count (1 to 100000)");
        bool logscale = form == "log" || (form == "random" && (*r)["log"].value_or(false));
        if (logscale && !(*from > 0 && *to > 0)) fail(line, form + ": a logarithmic range needs from > 0 and to > 0");
        auto lerp = [&](double u) {
            return logscale ? std::exp(std::log(*from) + u * (std::log(*to) - std::log(*from)))
                            : *from + u * (*to - *from);
        };
        if (form == "random") {
            // seeded by the sweep seed and the axis: the same samples on every machine and shard
            std::mt19937_64 rng(uint64_t(s.seed) * 1000003ull + s.axes.size());
            for (int64_t i = 0; i < *count; ++i) a.values.push_back(lerp(double(rng() >> 11) * 0x1.0p-53));
        } else {
            for (int64_t i = 0; i < *count; ++i)
                a.values.push_back(lerp(*count == 1 ? 0.0 : double(i) / double(*count - 1)));
        }
    }

    void axes(const toml::table& t) const {
        auto* vary = t["vary"].as_array();
        if (!vary || vary->empty()) fail(1, "missing [[vary]]: at least one varied parameter");
        for (auto& node : *vary) {
            auto* v = node.as_table();
            int line = line_of(node);
            if (!v) fail(line, "[[vary]] must be a table");
            SweepAxis a;
            a.line = line;
            const std::set<std::string> keys = {"layer", "key", "values", "linear", "log", "random"};
            for (auto& [k, x] : *v)
                if (!keys.count(std::string(k.str())))
                    fail(line_of(x), "unknown key '" + std::string(k.str()) +
                                         "' in [[vary]] (expected layer, key, and one of values, linear, log, random)");
            varied_parameter(*v, a, line);
            for (const SweepAxis& b : s.axes)   // sweep.csv would hold two columns of one name, one of them a lie
                if (b.layer == a.layer && b.key == a.key)
                    fail(line, "[[vary]]: " + axis_name(a) + " is varied already by the [[vary]] at line " +
                                   std::to_string(b.line) + "; vary a key once (give all its values there)");
            axis_values(*v, a, line);
            if (a.values.empty()) fail(line, "[[vary]]: no values");
            for (double x : a.values)   // as written, before a float holds it (1.00000001 is not a roughness)
                if (a.layer < 0 ? !find_stack_key(a.key)->admits(x)
                                : !find_layer_key(s.base.layers[size_t(a.layer)].kind, a.key)->admits(x))
                    fail(line, "[[vary]]: " + axis_name(a) + " = " + written_value_text(x) + " is outside its range " +
                                   range_text(a) + " (as in a stack file)");
            s.axes.push_back(a);
        }
    }

    // a [[fit]]'s model, free keys, starts and loss (model_fit.h FitSpec)
    SweepFit fit_spec(const toml::table& f, int line) const {
        const std::set<std::string> keys = {"model", "free", "start", "loss"};
        for (auto& [k, x] : f)
            if (!keys.count(std::string(k.str())))
                fail(line_of(x),
                     "unknown key '" + std::string(k.str()) + "' in [[fit]] (expected model, free, start, loss)");
        SweepFit fit;
        fit.line = line;
        auto model = f["model"].value<std::string>();
        if (!model) fail(line, "[[fit]]: missing model = \"ID\" (a built-in model; gonio models lists them)");
        fit.spec.model = *model;
        auto* free = f["free"].as_array();
        if (!free || free->empty())
            fail(line, "[[fit]]: missing free = [\"layer.N.KEY\", ...] (the stack keys the fit may change)");
        for (auto& k : *free) {
            auto v = k.value<std::string>();
            if (!v) fail(line_of(k), "[[fit]] free: expected keys as strings, e.g. \"layer.2.roughness\"");
            fit.spec.free.push_back(*v);
        }
        if (auto start = f["start"]) {
            auto* st = start.as_table();
            if (!st) fail(line_of(*start.node()), "[[fit]] start: expected an inline table {\"layer.N.KEY\" = value}");
            for (auto& [k, x] : *st) {
                // a value, or a list of values: the fit starts from each (every combination over the keys)
                std::vector<double> vs;
                if (auto* arr = x.as_array())
                    for (auto& e : *arr) vs.push_back(e.value<double>().value_or(NAN));
                else
                    vs.push_back(x.value<double>().value_or(NAN));
                if (vs.empty() || std::any_of(vs.begin(), vs.end(), [](double v) { return std::isnan(v); }))
                    fail(line_of(x),
                         "[[fit]] start: expected {\"layer.N.KEY\" = value or [values], ...}, the key in "
                         "quotes (" +
                             std::string(k.str()) + ")");
                fit.spec.start.push_back({std::string(k.str()), vs});
            }
        }
        if (auto loss = f["loss"]) {
            try {
                fit.spec.loss = parse_fit_loss(loss.value<std::string>().value_or(""));
            } catch (const std::invalid_argument& e) {
                fail(line_of(*loss.node()), std::string("[[fit]] ") + e.what());
            }
        }
        return fit;
    }

    // [[fit]] blocks, one per model: each must be possible on some configuration (its keys and starts are the same
    // on all; the model may not represent every configuration, which then has no fit)
    void fits(const toml::table& t) const {
        auto* node = t.get("fit");
        if (!node) return;
        auto* arr = node->as_array();
        if (!arr) fail(line_of(*node), "fit: expected [[fit]] tables (model, free, start, loss)");
        for (auto& e : *arr) {
            auto* f = e.as_table();
            if (!f) fail(line_of(e), "[[fit]] must be a table");
            const SweepFit fit = fit_spec(*f, line_of(e));
            for (const SweepFit& other : s.fits)
                if (other.spec.model == fit.spec.model)
                    fail(fit.line, "[[fit]]: a second fit of " + fit.spec.model + " (the first at line " +
                                       std::to_string(other.line) + "): one [[fit]] per model (its columns are fit." +
                                       fit.spec.model + ".*)");
            s.fits.push_back(fit);   // checked once the model files are read (check_sweep_fits)
        }
    }
};

}   // namespace

Sweep parse_sweep_file(const std::string& path) {
    Sweep s;
    s.path = path;
    s.text = read_text(path);
    toml::table t;
    try {
        t = toml::parse(s.text, path);
    } catch (const toml::parse_error& e) {
        throw StackError(path, int(e.source().begin.line), "invalid TOML: " + std::string(e.description()));
    }
    const SweepParser p{s};
    p.top_keys(t);
    auto name = t["name"].value<std::string>();
    if (!name || name->empty()) p.fail(1, "missing name = \"...\"");
    s.name = *name;
    auto stack = t["stack"].value<std::string>();
    if (!stack) p.fail(1, "missing stack = \"path/to/stack.toml\" (relative to the sweep file)");
    s.base = parse_stack_file(p.beside(*stack).string());
    const std::string model_texts = p.model_files(t);
    p.selected_models(t);
    p.run_options(t);
    p.axes(t);
    if (s.configurations() > 100000000ull) p.fail(1, "more than 1e8 configurations: split the sweep");
    s.hash = fnv1a(s.text, fnv1a(s.base.source_text));
    if (!model_texts.empty()) s.hash = fnv1a(model_texts, s.hash);
    for (uint64_t i = 0; i < s.configurations(); ++i) s.stack(i);   // every configuration is valid, or say which is not
    p.spectral(t);
    p.fits(t);
    if (s.spectral.on && !s.fits.empty())
        p.fail(s.fits.front().line,
               "[[fit]] with [spectral]: a fit matches a model to an RGB reference (gonio fit); run the fits in a "
               "sweep of their own");
    return s;
}

void check_sweep_fits(const Sweep& s, const std::vector<std::shared_ptr<const UserModel>>& user_models) {
    for (const SweepFit& fit : s.fits) {
        // possible on some configuration: its keys and starts are the same on all, the model may not represent all
        std::string why;
        const uint64_t n = std::min<uint64_t>(s.configurations(), 10000);
        for (uint64_t i = 0; i < n; ++i) {
            try {
                fit_options_for(s.stack(i), fit.spec, user_models);
                why.clear();
                break;
            } catch (const std::invalid_argument& x) { why = x.what(); }
        }
        if (!why.empty()) throw StackError(s.path, fit.line, "[[fit]]: " + why);
    }
}

ShardSpec parse_shard(const std::string& text) {
    auto slash = text.find('/');
    ShardSpec sh;
    try {
        if (slash == std::string::npos) throw std::invalid_argument("");
        sh.index = std::stoull(text.substr(0, slash));
        sh.count = std::stoull(text.substr(slash + 1));
    } catch (...) { throw std::invalid_argument("--shard: expected K/N, e.g. 3/64"); }
    if (sh.count < 1 || sh.index < 1 || sh.index > sh.count)
        throw std::invalid_argument("--shard K/N needs 1 <= K <= N");
    return sh;
}

namespace {

std::string config_path(const std::string& dir, uint64_t i) {
    char b[48];
    std::snprintf(b, sizeof b, "/configs/c-%08llu.csv", (unsigned long long)i);
    return dir + b;
}

std::string header_line(const Sweep& s) {
    std::string h = "config";
    for (auto& a : s.axes) h += "," + column_name(a);
    if (s.spectral.on) return h + "," + kSpectralSweepColumns;
    h += s.phi_i_deg != 0.0 ? ",theta_i,phi_i" : ",theta_i";   // the azimuth's column where it is not 0
    h += ",side,model,rmse_remapped,mean_abs_error_remapped,rmse_linear,mean_relative_error_linear,"
         "albedo_model_r,albedo_model_g,albedo_model_b,albedo_reference_r,albedo_reference_g,albedo_reference_b,"
         "reference_noise_remapped,within_reference_noise,reference_paths,reference_worst_rse,"
         "chi2_per_dof,mean_z,chi2_p_value,bias_p_value,smallest_detectable_relative_bias,best,tied_with_best";
    for (const SweepFit& f : s.fits) {   // the configuration's fits, the same on each of its rows
        const std::string m = "fit." + f.spec.model + ".";
        for (const std::string& k : f.spec.free) h += "," + m + k + "," + m + k + ".se," + m + k + ".status";
        h += "," + m + "loss";
    }
    return h;
}

// A configuration file's last line: "# end HASH I crc32c C", C the CRC-32C of its rows (crc32c.h)
std::string end_line(uint64_t hash, uint64_t i, const std::string& rows) {
    char c[16];
    std::snprintf(c, sizeof c, "%08x", unsigned(crc32c_update(0, rows.data(), rows.size())));
    return "# end " + hex(hash) + " " + std::to_string(i) + " crc32c " + c;
}

constexpr const char* kTruncated = "truncated (no end line)";
constexpr const char* kDamaged = "damaged (its rows differ from their CRC-32C)";

// A configuration file: "# gonio sweep HASH config I", rows, end_line (or "# end HASH I", without the CRC, as an
// earlier gonio wrote it). Complete, undamaged and of this sweep?
bool config_complete(const std::string& path, uint64_t hash, uint64_t i, std::string* rows, std::string* why) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        if (why) *why = "missing";
        return false;
    }
    std::string first, line, body, last;
    std::getline(f, first);
    if (first != "# gonio sweep " + hex(hash) + " config " + std::to_string(i)) {
        if (why)
            *why = first.rfind("# gonio sweep ", 0) == 0 ? "written by another sweep (its hash differs)"
                                                         : "not a gonio sweep file";
        return false;
    }
    while (std::getline(f, line)) {
        if (line.rfind("# end ", 0) == 0) {
            last = line;
            break;
        }
        body += line + "\n";
    }
    const std::string end = "# end " + hex(hash) + " " + std::to_string(i);
    if (last != end && last.rfind(end + " crc32c ", 0) != 0) {
        if (why) *why = kTruncated;
        return false;
    }
    if (last != end && last != end_line(hash, i, body)) {
        if (why) *why = kDamaged;
        return false;
    }
    if (rows) *rows = body;
    return true;
}

void write_atomically(const std::string& path, const std::string& text) {
    std::string tmp = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        f.flush();
        if (!f) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw std::runtime_error("cannot write " + path + " (disk full?); rerun with --resume once there is room");
        }
    }
    fs::rename(tmp, path);
}

// DIR/sweep.json: which sweep the directory holds (its hash), how many configurations, sweep.csv's header line.
Json manifest(const Sweep& s) {
    return {{"name", s.name},
            {"sweep_file", s.path},
            {"hash", hex(s.hash)},
            {"configurations", s.configurations()},
            {"header", header_line(s)}};
}

}   // namespace

bool sweep_specialised(const Sweep& s) {
    WalkSpec first = walk_spec(s.stack(0), true);
    for (uint64_t i = 1; i < s.configurations(); ++i) {
        WalkSpec w = walk_spec(s.stack(i), true);
        // one specialised pipeline per sweep: the same rough, absorbing and scattering layers, and the Lambertian series
        // for all configurations or none (it may not apply to some: a coat that traps too much light)
        if (!(w == first)) return false;
    }
    return true;
}

namespace {

// The [[fit]] columns of a configuration (each with its leading comma): per fit, per free key its value, standard
// error and status (fitted, at-limit, unconstrained: no value and no se), then the loss at the fit; where the model
// cannot represent the configuration's stack, empty values and status not-fitted, and the reason on stderr
std::string fit_columns(const Sweep& s, uint64_t i, const Stack& stack, const SimResult& r, ModelEvaluator& ev,
                        const ModelOptions& mo) {
    std::string out;
    for (const SweepFit& sf : s.fits) {
        FitResult f;
        std::string why;
        try {
            FitOptions fo = fit_options_for(stack, sf.spec, mo.user_models);
            fo.models = mo;
            f = fit_model(ev, r, stack, fo);
        } catch (const std::invalid_argument& e) { why = e.what(); }
        if (!why.empty())
            std::fprintf(stderr, "gonio: configuration %llu: %s not fitted: %s\n", (unsigned long long)i,
                         sf.spec.model.c_str(), why.c_str());
        for (const FitParameter& p : f.parameters) {
            const char* status = !p.constrained ? "unconstrained" : p.at_limit ? "at-limit" : "fitted";
            out += "," + (p.constrained ? num(p.value) + "," + num(p.se) : std::string(",")) + "," + status;
        }
        if (!why.empty())
            for (size_t k = 0; k < sf.spec.free.size(); ++k) out += ",,,not-fitted";
        out += "," + (why.empty() ? num(f.loss_best) : std::string());
    }
    return out;
}

// The rows of configuration i; `fits`: its [[fit]] columns.
// ",phi_i" after theta_i where the sweep has an azimuth, "" in the plane of incidence
std::string phi_i_column(const Sweep& s) { return s.phi_i_deg != 0.0 ? "," + num(s.phi_i_deg) : ""; }

std::string config_rows(const Sweep& s, uint64_t i, const SimResult& r, const std::vector<ModelSlices>& ms,
                        const Comparison& c, const std::string& fits) {
    std::string text;
    const std::string prefix = config_prefix(s, i);
    for (size_t k = 0; k < ms.size(); ++k) {
        const ModelSlices& m = ms[k];
        if (!model_has_bins(m)) continue;
        for (int side = 0; side < 2; ++side) {
            const std::vector<ModelMetrics>& metrics = c.models[k].side(Side(side));
            for (size_t a = 0; a < metrics.size(); ++a) {
                const ModelMetrics& mm = metrics[a];
                const Agreement& ag = mm.agreement;
                const BestModel* b = a < c.best[side].size() ? &c.best[side][a] : nullptr;
                const bool is_best = b && b->best == m.id, tied = b && (is_best || (b->tie && b->runner_up == m.id));
                text += prefix + "," + num(s.theta_i_deg[a]) + phi_i_column(s) + "," + (side ? "T" : "R") + "," + m.id +
                        "," + num(mm.rmse_remapped) + "," + num(mm.mean_abs_remapped) + "," + num(mm.rmse_linear) +
                        "," + num(mm.mean_rel_linear) + "," + num(mm.albedo_model.x) + "," + num(mm.albedo_model.y) +
                        "," + num(mm.albedo_model.z) + "," + num(mm.albedo_reference.x) + "," +
                        num(mm.albedo_reference.y) + "," + num(mm.albedo_reference.z) + "," +
                        num(mm.reference_noise_remapped) + "," + (mm.within_noise ? "1" : "0") + "," +
                        std::to_string(r.angles[a].paths) + "," + num(r.angles[a].worst_rse) + "," +
                        num(ag.chi2_per_dof) + "," + num(ag.mean_z) + "," + num(ag.chi2_p_value) + "," +
                        num(ag.bias_p_value) + "," + num(ag.smallest_detectable_relative_bias) + "," +
                        (is_best ? "1" : "0") + "," + (tied ? "1" : "0") + fits + "\n";
            }
        }
    }
    // the reference's own row per side and angle, model "reference": its albedo, paths and worst rse, the models'
    // fields empty; so a configuration that no model can represent (a backward-scattering medium for Belcour's)
    // still says what the reference measured
    for (int side = 0; side < int(r.n_sides); ++side)
        for (size_t a = 0; a < r.angles.size(); ++a) {
            const Slice sl = make_slice(r, a, side ? kTransmission : kReflection);
            const BinGrid g(r);
            glm::dvec3 albedo(0.0);   // as compare_model sums it: f times the bin's projected solid angle
            for (uint32_t t = 0; t < g.n_theta; ++t)
                for (uint32_t p = 0; p < g.n_phi; ++p)
                    albedo += sl.f[size_t(t) * g.n_phi + p] * g.projected_solid_angle(t);
            text += prefix + "," + num(s.theta_i_deg[a]) + phi_i_column(s) + "," + (side ? "T" : "R") +
                    ",reference,,,,,,,," + num(albedo.x) + "," + num(albedo.y) + "," + num(albedo.z) + ",,," +
                    std::to_string(r.angles[a].paths) + "," + num(r.angles[a].worst_rse) + ",,,,,,0,0" + fits + "\n";
        }
    return text;
}

}   // namespace

SimOptions sweep_sim_options(const Sweep& s, bool specialised) {
    SimOptions so;
    so.theta_i_deg = s.theta_i_deg;
    so.phi_i_deg = s.phi_i_deg;
    so.paths = s.paths;
    so.rse_target = s.rse;
    so.rse_quantile = s.rse_quantile;
    so.max_events = s.max_events;
    so.progress = false;
    so.specialised = specialised;
    return so;
}

std::string config_prefix(const Sweep& s, uint64_t i) {
    std::string prefix = std::to_string(i);
    for (double v : s.values(i)) prefix += "," + num(v);
    return prefix;
}

void write_config(const Sweep& s, const std::string& dir, uint64_t i, const std::string& rows, double seconds) {
    const std::string path = config_path(dir, i);
    write_atomically(path, "# gonio sweep " + hex(s.hash) + " config " + std::to_string(i) + "\n" + rows +
                               end_line(s.hash, i, rows) + "\n");
    write_atomically(path.substr(0, path.size() - 4) + ".seconds", num(seconds) + "\n");
}

std::string config_result_dir(const std::string& dir, uint64_t i) {
    const std::string path = config_path(dir, i);
    return path.substr(0, path.size() - 4);
}

void print_sweep_progress(const Sweep& s, const SweepRunOptions& o, uint64_t done, uint64_t mine, uint64_t computed,
                          uint64_t left, double elapsed_seconds) {
    const double eta = elapsed_seconds / double(std::max<uint64_t>(computed, 1)) * double(left);
    std::fprintf(stderr, "\rsweep %s: %llu/%llu configurations of shard %llu/%llu, ETA %.0f s   ", s.name.c_str(),
                 (unsigned long long)done, (unsigned long long)mine, (unsigned long long)o.shard.index,
                 (unsigned long long)o.shard.count, eta);
}

std::vector<uint64_t> sweep_todo(const Sweep& s, const std::string& dir, const SweepRunOptions& o, uint64_t& mine) {
    fs::create_directories(dir + "/configs");
    const std::string man = dir + "/sweep.json";
    if (fs::exists(man)) {
        const Json m = read_json_file(man);
        if (!m.is_object() || m.value("hash", Json()) != hex(s.hash))
            throw std::invalid_argument(dir + " holds another sweep (" + man + " has another hash): use another --out");
    } else {
        write_atomically(man, json_text(manifest(s)));
    }
    const uint64_t n = s.configurations();
    // what this shard still has to do
    std::vector<uint64_t> todo;
    mine = 0;
    for (uint64_t i = o.shard.index - 1; i < n; i += o.shard.count) {
        mine++;
        const std::string path = config_path(dir, i);
        std::string why;
        if (config_complete(path, s.hash, i, nullptr, &why)) {
            if (!o.resume)
                throw std::invalid_argument(dir + " already has configuration " + std::to_string(i) +
                                            " of this sweep: add --resume to continue it, or choose another --out");
            continue;
        }
        if (fs::exists(path) && why != kTruncated && why != kDamaged)   // this sweep's own, cut or damaged: rerun
            throw std::invalid_argument(path + ": " + why + ": refusing to overwrite it");
        todo.push_back(i);
    }
    return todo;
}

uint64_t run_sweep(VkContext& ctx, const Sweep& s, const std::string& dir, const SweepRunOptions& o) {
    uint64_t mine = 0;
    const std::vector<uint64_t> todo = sweep_todo(s, dir, o, mine);
    const bool specialised = sweep_specialised(s);
    const SimOptions so = sweep_sim_options(s, specialised);
    ModelEvaluator models(ctx);
    uint64_t computed = 0;
    auto t0 = std::chrono::steady_clock::now();
    const size_t B = std::max<uint32_t>(1, o.batch);
    for (size_t first = 0; first < todo.size(); first += B) {
        auto c0 = std::chrono::steady_clock::now();
        std::vector<uint64_t> ids(todo.begin() + long(first), todo.begin() + long(std::min(todo.size(), first + B)));
        std::vector<Stack> stacks;
        std::vector<uint32_t> seeds;
        for (uint64_t i : ids) {
            stacks.push_back(s.stack(i));
            seeds.push_back(s.config_seed(i));
        }
        std::vector<SimResult> refs = simulate_gpu_batch(ctx, stacks, seeds, so);
        for (size_t k = 0; k < ids.size(); ++k)   // a path that booked a non-finite number (walk.glsl): stop, say where
            for (size_t a = 0; a < refs[k].angles.size(); ++a)
                if (refs[k].angles[a].energy[9] != 0)
                    throw std::runtime_error("configuration " + std::to_string(ids[k]) + ", theta_i " +
                                             num(s.theta_i_deg[a]) +
                                             ": paths booked a number that is not finite (the invalid class): a bug, "
                                             "please report it with the sweep file");
        double ref_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count() / double(ids.size());
        for (size_t k = 0; k < ids.size(); ++k) {
            auto m0 = std::chrono::steady_clock::now();
            std::vector<ModelCost> costs;
            std::vector<ModelSlices> ms = models.evaluate(stacks[k], model_grid(refs[k]), &costs, o.models);
            for (const ModelSlices& m : ms)   // no rows in sweep.csv for it: say why
                if (!m.invalid.empty())
                    std::fprintf(stderr, "gonio: configuration %llu: %s not scored: %s\n", (unsigned long long)ids[k],
                                 m.id.c_str(), m.invalid.c_str());
            const Comparison cmp = compare_models(refs[k], ms);
            if (o.keep_results) {
                // configs/c-N/: what compare writes (EXR, slices.csv, summary.json), written into a temporary
                // directory and renamed before the configuration's row file, which marks it done
                const std::string rdir = config_result_dir(dir, ids[k]),
                                  tmp = rdir + ".tmp" + std::to_string(::getpid());
                std::error_code ec;
                fs::remove_all(tmp, ec);
                fs::create_directories(tmp);
                write_exr(tmp + "/" + safe_file_name(stacks[k].name) + ".exr", refs[k], &ms);
                write_slices_csv(tmp + "/slices.csv", refs[k], &ms);
                const Json models_summary = models_json(refs[k], ms, cmp, costs);
                write_summary_json(tmp + "/summary.json", refs[k], &models_summary);
                fs::remove_all(rdir, ec);
                fs::rename(tmp, rdir);
            }
            const std::string fits = fit_columns(s, ids[k], stacks[k], refs[k], models, o.models);
            const double sec =
                ref_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - m0).count();
            write_config(s, dir, ids[k], config_rows(s, ids[k], refs[k], ms, cmp, fits), sec);
            computed++;
        }
        if (o.progress)
            print_sweep_progress(s, o, mine - todo.size() + computed, mine, computed, todo.size() - computed,
                                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    if (o.progress) std::fprintf(stderr, "\n");
    return computed;
}

Json bench_sweep(VkContext& ctx, const Sweep& s, uint64_t count, const ModelOptions& mo) {
    count = std::min(count, s.configurations());
    const bool specialised = sweep_specialised(s);
    std::vector<Stack> stacks;
    std::vector<uint32_t> seeds;
    for (uint64_t i = 0; i < count; ++i) {
        stacks.push_back(s.stack(i));
        seeds.push_back(s.config_seed(i));
    }
    // batched, as gonio sweep runs them (one evaluator for all)
    auto t0 = std::chrono::steady_clock::now();
    {
        std::vector<SimResult> refs = simulate_gpu_batch(ctx, stacks, seeds, sweep_sim_options(s, specialised));
        ModelEvaluator ev(ctx);
        for (uint64_t i = 0; i < count; ++i) ev.evaluate(stacks[i], model_grid(refs[i]), nullptr, mo);
    }
    double batched = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // one at a time, as a loop of gonio compare does: its own walk, pipelines and tables each time
    auto t1 = std::chrono::steady_clock::now();
    for (uint64_t i = 0; i < count; ++i) {
        SimOptions so = sweep_sim_options(s, true);
        so.seed = seeds[i];
        SimResult r = simulate_gpu(ctx, stacks[i], so);
        evaluate_models(ctx, stacks[i], model_grid(r), nullptr, mo);
    }
    double loop = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    return {{"sweep", s.name},
            {"device", ctx.device_info().name},
            {"configurations", count},
            {"angles", s.theta_i_deg.size()},
            {"paths_per_angle", s.paths},
            {"batched_seconds", json_fixed(batched, 4)},
            {"compare_loop_seconds", json_fixed(loop, 4)},
            {"batched_configurations_per_second", json_fixed(double(count) / batched, 4)},
            {"compare_loop_configurations_per_second", json_fixed(double(count) / loop, 4)},
            {"speedup", json_fixed(loop / batched, 3)}};
}

uint64_t merge_sweep(const std::string& dir) {
    const std::string man = dir + "/sweep.json";
    if (!fs::exists(man)) throw std::invalid_argument(dir + " is not a sweep output (no sweep.json)");
    const Json m = read_json_file(man);
    auto field = [&](const std::string& key, Json::value_t type) {
        if (!m.is_object() || !m.contains(key)) throw std::invalid_argument(man + ": no " + key);
        const Json& v = m[key];
        if (v.type() != type)
            throw std::invalid_argument(man + ": " + key + " is not " +
                                        (type == Json::value_t::string ? "a string" : "a whole number"));
        return v;
    };
    uint64_t hash = 0;
    try {
        hash = std::stoull(field("hash", Json::value_t::string).get<std::string>(), nullptr, 16);
    } catch (const std::logic_error&) { throw std::invalid_argument(man + ": hash is not a hexadecimal number"); }
    const uint64_t n = field("configurations", Json::value_t::number_unsigned).get<uint64_t>();
    const std::string header = field("header", Json::value_t::string).get<std::string>();
    std::string out = header + "\n", timings = "config,seconds\n";
    std::vector<std::string> problems;
    uint64_t rows = 0;
    for (uint64_t i = 0; i < n; ++i) {
        std::string body, why;
        if (!config_complete(config_path(dir, i), hash, i, &body, &why)) {
            if (problems.size() < 10)
                problems.push_back("configuration " + std::to_string(i) + ": " + why);
            else if (problems.size() == 10)
                problems.push_back("...");
            continue;
        }
        out += body;
        for (char c : body) rows += c == '\n';
        std::string p = config_path(dir, i);
        std::ifstream tf(p.substr(0, p.size() - 4) + ".seconds");
        std::string sec;
        std::getline(tf, sec);
        timings += std::to_string(i) + "," + (sec.empty() ? "" : sec) + "\n";
    }
    if (!problems.empty()) {
        std::string msg = "cannot merge " + dir + ": ";
        for (size_t k = 0; k < problems.size(); ++k) msg += (k ? "; " : "") + problems[k];
        throw std::invalid_argument(msg + " (run the missing shards, or rerun with --resume)");
    }
    write_atomically(dir + "/sweep.csv", out);
    write_atomically(dir + "/timings.csv", timings);
    return rows;
}

}   // namespace gonio
