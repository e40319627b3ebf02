#include "simulate_run.h"
#include "model_table.h"
#include "histogram.h"
#include "output.h"
#include "state.h"
#include "validation.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

namespace fs = std::filesystem;

namespace gonio {

Stack stack_operand(const std::string& cmd, const std::vector<std::string>& operands) {
    if (operands.size() != 1) usage_error(cmd + " takes one stack file");
    return parse_stack_file(operands[0]);
}

namespace {

// --resume: the options the earlier run recorded, for those not given again (given ones are checked against them)
void continue_with_recorded_options(const SimOptions& recorded, const std::set<std::string>& given, SimOptions& o) {
    auto take = [&given](const char* name, auto& value, const auto& recorded_value) {
        if (!given.count(name)) value = recorded_value;
    };
    take("--theta-i", o.theta_i_deg, recorded.theta_i_deg);
    take("--seed", o.seed, recorded.seed);
    take("--dtheta", o.dtheta_deg, recorded.dtheta_deg);
    take("--dphi", o.dphi_deg, recorded.dphi_deg);
    take("--max-events", o.max_events, recorded.max_events);
    take("--orders", o.orders, recorded.orders);
    take("--general-walk", o.specialised, recorded.specialised);
    take("--no-series", o.series, recorded.series);
    take("--no-branching", o.branching, recorded.branching);
    take("--no-baked-stack", o.baked_stack, recorded.baked_stack);
    take("--paths", o.paths, recorded.paths);
    take("--rse", o.rse_target, recorded.rse_target);
    take("--rse-quantile", o.rse_quantile, recorded.rse_quantile);
    take("--max-seconds", o.max_seconds, recorded.max_seconds);
}

}   // namespace

SimulateRun prepare_run(const WalkSettings& w, Stack s) {
    SimulateRun run{std::move(s), w.sim, "", std::nullopt};
    if (!w.resume.empty()) {
        run.previous = load_state(w.resume + "/state.gonio");
        continue_with_recorded_options(run.previous->options, w.given, run.sim);
    }
    // --rse without --paths: paths are the cap, 1e10 (a resumed run keeps its recorded cap unless --rse is new)
    if (run.sim.rse_target > 0 && !w.paths_given && (w.resume.empty() || w.given.count("--rse")))
        run.sim.paths = 10000000000ull;
    validate_options(run.sim);
    run.out = w.out.empty() ? (w.resume.empty() ? "out/" + safe_file_name(run.stack.name) : w.resume) : w.out;
    if (run.previous) check_resumable(*run.previous, run.stack, run.sim);
    fs::create_directories(run.out);
    if (w.checkpoint_seconds > 0) {   // a killed run leaves at most this much work undone (--resume DIR continues it)
        run.sim.checkpoint_seconds = w.checkpoint_seconds;
        run.sim.on_checkpoint = [out = run.out](const SimResult& partial) {
            save_state(out + "/state.gonio", partial);
        };
    }
    return run;
}

int write_run(const SimulateRun& run, const SimResult& r, const std::vector<ModelSlices>* models,
              const Json* models_summary) {
    const std::string& out = run.out;
    const std::string name = safe_file_name(run.stack.name);
    int rc = 0;
    write_exr(out + "/" + name + ".exr", r, models);
    write_slices_csv(out + "/slices.csv", r, models);
    write_summary_json(out + "/summary.json", r, models_summary);
    save_state(out + "/state.gonio", r);
    for (size_t i = 0; i < r.angles.size(); ++i) {
        EnergyBook e = energy_book(r, i);
        if (e.invalid.x > 0) {   // walk.glsl path_is_finite: booked apart, never as absorbed or leaving
            std::fprintf(stderr,
                         "gonio: theta_i %g: %.0f paths booked a number that is not finite (summary.json: energy "
                         "invalid %.3g): a bug, please report it with the stack file and the command\n",
                         r.angles[i].theta_i_deg, e.invalid.x * double(r.angles[i].paths), e.invalid.x);
            rc = 1;
        }
        std::printf("theta_i %5g: R %.5f %.5f %.5f, T %.5f %.5f %.5f, %llu paths (%s), median rse %.4f, worst %.3f\n",
                    r.angles[i].theta_i_deg, e.reflected.x, e.reflected.y, e.reflected.z, e.transmitted.x,
                    e.transmitted.y, e.transmitted.z, (unsigned long long)r.angles[i].paths,
                    r.angles[i].stopped_by.c_str(), r.angles[i].median_rse, r.angles[i].worst_rse);
    }
    const std::vector<ModelSlices> none;
    print_model_metrics(r, models ? *models : none);
    for (const ModelSlices& m : models ? *models : none)
        if (!m.invalid.empty()) {   // never scored: summary.json says where
            std::fprintf(stderr, "gonio: %s: its bins cannot be used: %s\n", m.id.c_str(), m.invalid.c_str());
            rc = 1;
        }
    std::printf("wrote %s/{%s.exr,slices.csv,summary.json,state.gonio}\n", out.c_str(), name.c_str());
    return std::max(rc, check_finite_json());
}

}   // namespace gonio
