#include "cmd_simulate.h"
#include "common_options.h"
#include "simulate_run.h"
#include "validation.h"
#include "vk_context.h"

#include <algorithm>
#include <cstdio>
#include <thread>

namespace gonio {

namespace {

constexpr const char* kSimulateNotes = R"(simulate writes, in DIR:
  <name>.exr      OpenEXR, one part per incident angle and side (R: reflection, T: transmission);
                  rows = theta bins, columns = phi bins (centred on multiples of dphi); channels R,G,B
                  (bin average of f, 1/sr) and se.R, se.G, se.B (standard errors); header: stack, angles,
                  paths, seed, device, gonio version
  slices.csv      one row per bin: source,theta_i,side,theta_lo,theta_hi,phi_lo,phi_hi,r,g,b,se_r,se_g,se_b
  summary.json    per incident angle and channel: reflected, transmitted, absorbed, microfacet_loss and
                  truncated energy fractions (they sum to 1); paths, seconds, paths per second, device
  state.gonio     the run's sums, what --resume DIR continues from
)";

struct SimulateSettings {
    WalkSettings walk;
    bool cpu_twin = false;
};

OptionTable simulate_options(SimulateSettings& a) {
    return walk_options(a.walk) + OptionTable{{"--cpu-twin", nullptr,
                                               "run the walk on the CPU (same shader sources via GLM) instead of the "
                                               "device",
                                               [&a](const std::string&) { a.cpu_twin = true; }}};
}

int run_simulate(SimulateSettings& a, const std::vector<std::string>& operands) {
    Stack s = stack_operand("simulate", operands);
    if (a.cpu_twin && !a.walk.resume.empty()) usage_error("--resume works with the device walk only");
    const SimulateRun run = prepare_run(a.walk, std::move(s));
    SimResult r;
    int rc = 0;
    if (a.cpu_twin) {
        r = simulate_cpu(run.stack, run.sim, std::max(1u, std::thread::hardware_concurrency()));
    } else {
        VkContext ctx(a.walk.ctx);
        if (run.sim.progress) std::fprintf(stderr, "gonio: device %s\n", ctx.device_info().name.c_str());
        r = simulate_gpu(ctx, run.stack, run.sim, run.resumed());
        rc = check_validation(ctx);
    }
    return std::max(rc, write_run(run, r, nullptr, nullptr));
}

}   // namespace

Command simulate_command() {
    return {"simulate", "STACK.toml [options]", "trace paths through the stack, write calibrated BRDF/BTDF histograms",
            kSimulateNotes, invocation(&simulate_options, &run_simulate)};
}

}   // namespace gonio
