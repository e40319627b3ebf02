#include "common_options.h"
#include "text_format.h"
#include "user_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace gonio {

namespace {

// --theta-i for a run: the angles of a list, none twice (the library takes an angle twice, as independent replicates
// with a stream each, but the outputs name their parts by angle)
std::vector<double> distinct_angles(const std::string& opt, const std::string& v) {
    const std::vector<double> t = parse_list(opt, v);
    for (size_t k = 0; k < t.size(); ++k)
        for (size_t j = 0; j < k; ++j)
            if (t[k] == t[j]) usage_error(opt + ": the incident angle " + format_g9(t[k]) + " is given twice");
    return t;
}

// The walk's options that tune how it runs, not what it measures.
OptionTable walk_tuning_options(WalkSettings& w) {
    SimOptions& o = w.sim;
    return {
        {"--general-walk", nullptr, "use the general N-layer walk instead of the stack-specialised shader",
         [&o](const std::string&) { o.specialised = false; }},
        {"--no-series", nullptr,
         "trace every trip between a Lambertian base and its coat instead of summing them as the Lambertian series "
         "(docs/PHYSICS.md; the default where it applies: a dielectric coat over a Lambertian base, without --orders)",
         [&o](const std::string&) { o.series = false; }},
        {"--no-branching", nullptr,
         "the analog walk: every event takes one branch and a path books its one exit, instead of the entry's both "
         "branches and the exit estimates (docs/PHYSICS.md, \"Booking estimators\"; the default where they apply: a "
         "dielectric coat over an opaque base, without the Lambertian series). The same expectation, more variance",
         [&o](const std::string&) { o.branching = false; }},
        {"--no-baked-stack", nullptr,
         "read the stack's parameters from a uniform buffer at run time instead of compiling them into the shader "
         "(the default for a specialised walk of one or two layers; docs/PERFORMANCE.md). The same paths and "
         "estimator; the last bits of rounding can differ, and this is what a sweep's batches compute: use it to "
         "reproduce one configuration of a sweep byte for byte",
         [&o](const std::string&) { o.baked_stack = false; }},
        device_option(w.ctx),
        validate_option(w.ctx),
        {"--quiet", nullptr, "no progress line", [&o](const std::string&) { o.progress = false; }},
        {"--invalid-path-for-tests", "N", "makes path N's weight NaN (gonio's tests of the invalid class)",
         [&o](const std::string& v) {
             const uint64_t n = parse_count("--invalid-path-for-tests", v);
             if (n >= 0xffffffffull) usage_error("--invalid-path-for-tests: a path index below 2^32 - 1");
             o.invalid_path_for_tests = uint32_t(n);
         },
         true},
    };
}

// The walk's options of how long it runs: --rse and its quantile, --max-seconds, the checkpoints and --resume.
OptionTable walk_stopping_options(WalkSettings& w) {
    SimOptions& o = w.sim;
    return {
        {"--rse", "R",
         "run until the relative standard errors of the bins above 1% of their slice's peak are below R (e.g. 0.01) "
         "at the --rse-quantile; paths grow in rounds of 2^20 x 2^k per angle, --paths is the cap (default then "
         "1e10). summary.json says what stopped each angle, and the median, 90th percentile and worst relative se",
         [&o](const std::string& v) {
             o.rse_target = parse_number("--rse", v);
             if (!(o.rse_target > 0 && o.rse_target < 1)) usage_error("--rse must be in (0, 1), e.g. 0.01");
         }},
        {"--rse-quantile", "Q",
         "which bins --rse stops on: the quantile Q of their relative standard errors (default 0.5, the median; 1: "
         "the worst bin, which can take hours)",
         [&o](const std::string& v) {
             o.rse_quantile = parse_number("--rse-quantile", v);
             if (!(o.rse_quantile > 0 && o.rse_quantile <= 1))
                 usage_error("--rse-quantile must be in (0, 1], e.g. 0.5 (the median) or 1 (the worst bin)");
         }},
        {"--checkpoint-seconds", "S",
         "write DIR/state.gonio atomically at least every S seconds of tracing (default 30; 0: only at the end): a "
         "killed run continues with the same command and --resume DIR, to the same bytes as one uninterrupted run",
         [&w](const std::string& v) {
             w.checkpoint_seconds = parse_number("--checkpoint-seconds", v);
             if (!(w.checkpoint_seconds >= 0))
                 usage_error("--checkpoint-seconds must be at least 0 (0: no checkpoints)");
         }},
        {"--max-seconds", "S",
         "stop an incident angle after S seconds (reported as stopped_by max_seconds); the angles run side by side, "
         "each taking its share of the time by paths",
         [&o](const std::string& v) {
             o.max_seconds = parse_number("--max-seconds", v);
             if (!(o.max_seconds > 0)) usage_error("--max-seconds must be positive");
         }},
        {"--angles-per-dispatch", "N",
         "trace at most N incident angles side by side in shared dispatches (default 0: every angle the device's "
         "memory holds; 1: one angle after the other). The same bytes",
         [&o](const std::string& v) {
             const uint64_t n = parse_count("--angles-per-dispatch", v);
             if (n > 65535) usage_error("--angles-per-dispatch: at most 65535 (workgroup rows of one dispatch)");
             o.angles_per_dispatch = uint32_t(n);
         }},
        {"--resume", "DIR",
         "continue the run whose output is in DIR (its state.gonio) with the options it recorded (--theta-i, --phi-i, "
         "--seed, --dtheta, --dphi, --max-events, --orders, --general-walk, --no-series, --no-branching, "
         "--no-baked-stack; --paths, --rse, "
         "--rse-quantile and --max-seconds, which may be given anew to run longer): the result is exactly that of one "
         "longer run. The stack file must be the one it ran; an option given again must agree (refused with the "
         "difference)",
         [&w](const std::string& v) { w.resume = v; }},
    };
}

}   // namespace

OptionTable walk_options(WalkSettings& w) {
    SimOptions& o = w.sim;
    const OptionTable what = {
        {"--theta-i", "A,B,...",
         "incident polar angles in degrees, in [0, 90) (default 0); an item FROM:TO:STEP is a range: 0:88:2 is 0, 2, "
         "..., 88",
         [&o](const std::string& v) { o.theta_i_deg = distinct_angles("--theta-i", v); }},
        {"--phi-i", "DEG",
         "the incident azimuth, degrees in [0, 360), of every --theta-i (default 0: the plane xz the phi bins are "
         "centred on; the bins stay in the surface's frame). Other than 0, slices.csv has a phi_i column, summary.json "
         "a phi_i per angle and the EXR's parts are named theta_i=A phi_i=B; --spectral, --rgb-vs-spectral, score, "
         "render's tables and the isotropic exports take 0 only",
         [&o](const std::string& v) { o.phi_i_deg = parse_number("--phi-i", v); }},
        {"--paths", "N", "paths per incident angle, e.g. 1e8 (default 1e6)",
         [&w](const std::string& v) {
             w.sim.paths = parse_count("--paths", v);
             w.paths_given = true;
         }},
        seed_option(o.seed, "random seed (same seed, same bytes) (default 1)"),
        {"--out", "DIR", "output directory (default out/<stack name>; with --resume, its DIR)",
         [&w](const std::string& v) { w.out = v; }},
        {"--dtheta", "D", "bin width in theta, degrees; divides 90 (default 1)",
         [&o](const std::string& v) { o.dtheta_deg = parse_number("--dtheta", v); }},
        {"--dphi", "P", "bin width in phi, degrees; divides 180 (default 2)",
         [&o](const std::string& v) { o.dphi_deg = parse_number("--dphi", v); }},
        {"--orders", nullptr,
         "also split the histograms by path class: 0 = top reflection only / direct transmission, 1 = one internal "
         "reversal (one trip to the base and back), 2 = two or more (inter-reflections). Classes sum exactly to the "
         "total",
         [&o](const std::string&) { o.orders = true; }},
        {"--max-events", "N",
         "event cap per path, at most 1e6; energy still inside is reported as truncated "
         "(default 256)",
         [&o](const std::string& v) {
             const uint64_t n = parse_count("--max-events", v);
             if (n > 1000000) usage_error("--max-events too large");
             o.max_events = uint32_t(n);
         }},
    };
    OptionTable all = what + walk_stopping_options(w) + walk_tuning_options(w);
    for (Option& opt : all)   // which were given: --resume continues with the state's values of the others
        opt.set = [&w, name = opt.name, set = opt.set](const std::string& v) {
            w.given.insert(name);
            set(v);
        };
    return all;
}

OptionTable model_options(ModelSettings& m) {
    return {
        {"--no-belcour-tables", nullptr,
         "Belcour's models without their FGD and TIR tables: Fresnel at the mean cosine, no TIR term, as the seed "
         "does for slabs. The tables are computed on the device for the stack's interfaces and cached in "
         "$GONIO_CACHE_DIR (default $XDG_CACHE_HOME/gonio or ~/.cache/gonio; GONIO_NO_CACHE=1 turns the cache off)",
         [&m](const std::string&) { m.models.belcour_tables = false; }},
        {"--models", "ID,ID,...|all",
         "run only these models (ids of `gonio models` or of --model files; the others are counted in one line "
         "and listed in summary.json as not selected); all: every model and its variants. Without it the models as "
         "their authors publish them run, and the --model files (not the variants, e.g. belcour18-forward+g2)",
         [&m](const std::string& v) {
             if (v == "all") {
                 m.models.selected.clear();
                 m.models.variants = true;
             } else {
                 m.models.selected = parse_model_ids(v);
             }
         }},
        {"--model", "FILE",
         "also run your own model, one GLSL file (repeatable; docs/MODELS.md \"Your own model\", "
         "examples/user_model.glsl): its header (// gonio-model: ID; optionally citation, represents, reciprocal, "
         "energy-conserving), then vec3 model_f(vec3 l, vec3 v), f in 1/sr without the cosine. Without represents it "
         "runs on every stack; gonio measures its reciprocity (f(l, v) against f(v, l) at 196 direction pairs) and its "
         "largest albedo on the stack, and prints them beside what the header claims (summary.json \"claims\", "
         "\"measured\"). Compiled before the simulation starts (a "
         "compile error: FILE:LINE, exit 2), integrated as a black box (graded at the stack's narrowest roughness "
         "about the mirror direction, then refined where the nodes disagree) and scored as the built-in models are. "
         "Values that are NaN, infinite or negative are reported with where they are (summary.json "
         "\"invalid_values\"), never scored or written, and the run exits 1",
         [&m](const std::string& v) { m.files.push_back(v); }, false, true},
    };
}

void load_model_files(ModelSettings& m, bool progress) {
    for (const std::string& f : m.files) {
        m.models.user_models.push_back(load_user_model(f));
        if (progress)
            std::fprintf(stderr, "gonio: model %s (%s) compiled in %.2f s\n",
                         m.models.user_models.back()->header.id.c_str(), f.c_str(),
                         m.models.user_models.back()->compile_seconds);
    }
    check_model_ids(m.models);
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

OptionTable render_along_options(RenderAlong& r) {
    return {
        {"--render", "ENV",
         "also render the reference and the models on a sphere under ENV (furnace, studio, a Blender map's name, "
         "FILE.exr; as gonio render --env) into DIR/render; report.html shows the figure and each model's relative "
         "L1 and HDR-FLIP beside the reference's floor (docs/RENDER.md), --model files' too. The render's table is "
         "its own: 0:88:2 in two halves of --render-paths per angle, seeded by --seed",
         [&r](const std::string& v) {
             r.env = v;
             if (r.env.empty()) usage_error("--render needs an environment (furnace, studio, a map's name, FILE.exr)");
         }},
        {"--render-size", "N", "the render's pixels across, 8 to 2048 (default 128)",
         [&r](const std::string& v) {
             const uint64_t n = parse_count("--render-size", v);
             if (n < 8 || n > 2048) usage_error("--render-size must be 8 to 2048 pixels, got " + std::to_string(n));
             r.size = uint32_t(n);
         }},
        {"--render-paths", "N", "the render's table, paths per angle, at least 2 (default 1e6)",
         [&r](const std::string& v) {
             r.paths = parse_count("--render-paths", v);
             r.paths_given = true;
             if (r.paths < 2) usage_error("--render-paths: at least 2 per angle (two halves)");
         }},
    };
}

void check_render_along(const RenderAlong& r) {
    if (r.env.empty() && (r.size != 0 || r.paths_given))
        usage_error("--render-size and --render-paths set up --render ENV, which is not given");
}

Option device_option(ContextOptions& c) {
    return {"--device", "I", "Vulkan device index (see `gonio devices`)",
            [&c](const std::string& v) { c.device_index = int(parse_count("--device", v)); }};
}

Option validate_option(ContextOptions& c) {
    return {"--validate", nullptr, "enable the Khronos validation layer; any message makes the run fail",
            [&c](const std::string&) { c.validation = true; }};
}

Option seed_option(uint32_t& seed, const std::string& help) {
    return {"--seed", "S", help, [&seed](const std::string& v) {
                const uint64_t n = parse_count("--seed", v);
                if (n > 0xffffffffull) usage_error("--seed must fit in 32 bits");
                seed = uint32_t(n);
            }};
}

OptionTable pick_options(const OptionTable& from, const std::vector<std::string>& names) {
    OptionTable t;
    for (const std::string& n : names) {
        const Option* o = find_option(from, n);
        if (!o) throw std::logic_error("pick_options: no option " + n);
        t.push_back(*o);
    }
    return t;
}

Option retold(const OptionTable& from, const std::string& name, const std::string& help) {
    Option o = pick_options(from, {name})[0];
    o.help = help;
    return o;
}

OptionTable operator+(OptionTable a, const OptionTable& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

}   // namespace gonio

namespace gonio {

OptionTable spectral_band_options(SpectralBands& b, bool& given, const std::string& with) {
    return {{"--bands", "W", "with " + with + ": the bands' width in nm, dividing 380-780 (default 10: 40 bands)",
             [&b, &given](const std::string& v) {
                 b.width_nm = parse_number("--bands", v);
                 given = true;
                 try {
                     b.check();
                 } catch (const std::invalid_argument& e) { usage_error(std::string("--bands: ") + e.what()); }
             }},
            {"--band-points", "K",
             "with " + with +
                 ": wavelengths per band, the midpoints of its K equal parts, each with 1/K of its paths; a band's "
                 "value their mean, the midpoint rule for its average (default 1: its centre)",
             [&b, &given](const std::string& v) {
                 const double k = parse_number("--band-points", v);
                 if (k != std::floor(k)) usage_error("--band-points takes a whole number, got " + v);
                 b.points = unsigned(std::max(0.0, std::min(k, 1e6)));
                 given = true;
                 try {
                     b.check();
                 } catch (const std::invalid_argument& e) { usage_error(std::string("--band-points: ") + e.what()); }
             }},
            {"--band-paths", "even|weight|measured",
             "with " + with +
                 ": share the paths between the passes by a pilot's noise (measured, the default: an eighth of "
                 "--paths per pass, then the shares that make the largest of X's, Y's and Z's errors least), by "
                 "their weight in X + Y + Z (weight, the default with --rse), or evenly (even: every band as many "
                 "paths)",
             [&b, &given](const std::string& v) {
                 try {
                     b.pass_paths = parse_pass_paths(v);
                     b.pass_paths_chosen = true;
                 } catch (const std::invalid_argument& e) { usage_error(std::string("--band-paths: ") + e.what()); }
                 given = true;
             }}};
}

}   // namespace gonio
