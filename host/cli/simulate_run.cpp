#include "simulate_run.h"
#include "output.h"
#include "state.h"

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
    take("--phi-i", o.phi_i_deg, recorded.phi_i_deg);
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

Case plan_run(const WalkSettings& w, Stack s) {
    Case run{std::move(s), w.sim, "", std::nullopt};
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
    return run;
}

Case prepare_run(const WalkSettings& w, Stack s) {
    Case run = plan_run(w, std::move(s));
    fs::create_directories(run.out);
    if (w.checkpoint_seconds > 0) {   // a killed run leaves at most this much work undone (--resume DIR continues it)
        run.sim.checkpoint_seconds = w.checkpoint_seconds;
        run.sim.on_checkpoint = [out = run.out](const SimResult& partial) {
            save_state(out + "/state.gonio", partial);
        };
    }
    return run;
}

}   // namespace gonio
