// rgb_vs_spectral.cpp: see rgb_vs_spectral.h.
#include "rgb_vs_spectral.h"
#include "colour_error.h"
#include "output.h"
#include "spectral_simulate.h"
#include "stack_spectral.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace gonio {

int run_rgb_vs_spectral(const Case& run, const SpectralBands& bands, RgbReduction reduction, VkContext& ctx) {
    int rc = 0;
    const SpectralResult spectral = trace_spectral(run, bands, &ctx, 1, rc);
    std::string clipped;
    Case rgb_run = run;
    rgb_run.stack = stack_reduced_to_rgb(run.stack, reduction, clipped);
    rgb_run.out = run.out + "/rgb";
    rgb_run.sim.on_checkpoint = nullptr;   // the RGB run keeps no state file: --resume is refused with --spectral
    rgb_run.sim.checkpoint_seconds = 0;
    std::filesystem::create_directories(rgb_run.out);
    if (run.sim.progress) std::fprintf(stderr, "gonio: the RGB run (reduction %s)\n", to_string(reduction));
    const auto start = std::chrono::steady_clock::now();
    const SimResult rgb = simulate_gpu(ctx, rgb_run.stack, rgb_run.sim);
    const std::array<double, 2> seconds{
        spectral.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
    const std::string spectral_dir = run.out + "/spectral";
    std::filesystem::create_directories(spectral_dir);
    write_spectral_exr(spectral_dir + "/" + safe_file_name(run.stack.name) + ".exr", spectral);
    write_spectral_summary(spectral_dir + "/summary.json", spectral);
    rgb_run.sim.progress = false;
    rc = std::max(rc, write_case(rgb_run, CaseResult{rgb, std::nullopt}));
    const std::vector<ColourErrorSlice> e = colour_error(spectral, rgb);
    write_colour_error(run.out, e, spectral, to_string(reduction), clipped, seconds);
    if (!clipped.empty())
        std::fprintf(stderr, "gonio: warning: the %s reduction: %s\n", to_string(reduction), clipped.c_str());
    for (const ColourErrorSlice& s : e)
        std::printf(
            "theta_i %g %s: albedo dE2000 %.2f (ITP %.1f); %zu lit bins: dE2000 median %.2f, p95 %.2f, max %.2f;"
            " dE_ITP median %.1f, p95 %.1f; noise %.2f\n",
            s.theta_i_deg, s.side == 0 ? "R" : "T", s.albedo_de.de2000, s.albedo_de.de_itp, s.lit, s.median_de2000,
            s.p95_de2000, s.max_de2000, s.median_de_itp, s.p95_de_itp, s.median_de2000_noise);
    std::printf(
        "the spectral run %.1f s, the RGB run %.1f s: at equal median error in X, Y and Z the spectral run costs "
        "%.2f times the RGB run\n",
        seconds[0], seconds[1], spectral_cost_at_equal_error(e, seconds));
    std::printf("wrote %s/rgb-vs-spectral.json, rgb-vs-spectral.csv, spectral/ and rgb/ (reduction %s)\n",
                run.out.c_str(), to_string(reduction));
    return rc;
}

}   // namespace gonio
