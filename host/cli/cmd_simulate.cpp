#include "cmd_simulate.h"
#include "common_options.h"
#include "simulate_run.h"
#include "spectral_simulate.h"
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
                  (with --phi-i other than 0: source,theta_i,phi_i,side,...)
  summary.json    per incident angle and channel: reflected, transmitted, absorbed, microfacet_loss and
                  truncated energy fractions (they sum to 1); paths, seconds, paths per second, device
  state.gonio     the run's sums, what --resume DIR continues from
with --spectral (docs/SPECTRAL.md), instead:
  <name>.exr      one part per incident angle and side; channels X, Y, Z (the bins under D65, 1/sr), se.X, se.Y,
                  se.Z, R, G, B (linear sRGB), band.NNN and se.band.NNN per band (NNN its centre, nm)
  summary.json    per incident angle: "spectral" (wavelength_nm, reflected, transmitted per band), "xyz" and
                  "srgb" (a perfect white reflector: Y = 1)
)";

struct SimulateSettings {
    WalkSettings walk;
    bool cpu_twin = false;
    bool spectral = false;
    bool bands_given = false;
    SpectralBands bands;
};

OptionTable simulate_options(SimulateSettings& a) {
    return walk_options(a.walk) +
           OptionTable{{"--cpu-twin", nullptr,
                        "run the walk on the CPU (same shader sources via GLM) instead of the "
                        "device",
                        [&a](const std::string&) { a.cpu_twin = true; }},
                       {"--spectral", nullptr,
                        "trace wavelengths: 380 to 780 nm in bands (--bands), each at its "
                        "centre, three per pass of the walk; measured materials and key spectra at each band, "
                        "every other key one value; bins in XYZ, sRGB and per band "
                        "(docs/SPECTRAL.md)",
                        [&a](const std::string&) { a.spectral = true; }}} +
           spectral_band_options(a.bands, a.bands_given, "--spectral");
}

int run_simulate(SimulateSettings& a, const std::vector<std::string>& operands) {
    Stack s = stack_operand("simulate", operands);
    if (a.cpu_twin && !a.walk.resume.empty()) usage_error("--resume works with the device walk only");
    if (a.bands_given && !a.spectral) usage_error("--bands and --band-paths go with --spectral");
    if (a.spectral && a.walk.sim.phi_i_deg != 0.0)
        usage_error("--phi-i goes with the RGB walk; --spectral takes the plane of incidence (phi_i 0)");
    const Case run = prepare_run(a.walk, std::move(s));
    if (a.spectral) {
        const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
        if (a.cpu_twin) return run_spectral_simulate(run, a.bands, nullptr, threads);
        VkContext ctx(a.walk.ctx);
        const int rc = run_spectral_simulate(run, a.bands, &ctx, threads);
        return std::max(rc, check_validation(ctx));
    }
    CaseResult r;
    int rc = 0;
    if (a.cpu_twin) {
        r.reference = simulate_cpu(run.stack, run.sim, std::max(1u, std::thread::hardware_concurrency()));
    } else {
        VkContext ctx(a.walk.ctx);
        if (run.sim.progress) std::fprintf(stderr, "gonio: device %s\n", ctx.device_info().name.c_str());
        r = run_case(ctx, run, nullptr);
        rc = check_validation(ctx);
    }
    return std::max(rc, write_case(run, r));
}

}   // namespace

Command simulate_command() {
    return {"simulate", "STACK.toml [options]", "trace paths through the stack, write calibrated BRDF/BTDF histograms",
            kSimulateNotes, invocation(&simulate_options, &run_simulate)};
}

}   // namespace gonio
