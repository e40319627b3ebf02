// spectral_bench.cpp: see spectral_bench.h.
#include "spectral_bench.h"
#include "colour_error.h"
#include "case.h"
#include "spectral_simulate.h"
#include "stack.h"

#include <chrono>
#include <cstdio>

namespace gonio {

int run_spectral_bench(const std::vector<std::string>& stacks, const SimOptions& sim, const ContextOptions& ctx_opt,
                       const SpectralBands& bands) {
    VkContext ctx(ctx_opt);
    std::printf("device %s; %zu bands of %g nm (%s paths per pass), theta_i %g, %llu paths (per pass on average)\n",
                ctx.device_info().name.c_str(), bands.count(), bands.width_nm, to_string(bands.pass_paths),
                sim.theta_i_deg.front(), (unsigned long long)sim.paths);
    std::printf("%-28s %9s %9s %-24s %-24s %s\n", "stack", "RGB s", "spect. s", "RGB s to 1% (X/Y/Z)",
                "spectral s to 1% (X/Y/Z)", "spectral / RGB at equal error");
    int rc = 0;
    for (const std::string& f : stacks) {
        Case run;
        run.stack = parse_stack_file(f);
        run.sim = sim;
        run.sim.progress = false;
        const SpectralResult spectral = trace_spectral(run, bands, &ctx, 1, rc);
        const auto start = std::chrono::steady_clock::now();
        const SimResult rgb = simulate_gpu(ctx, run.stack, run.sim);
        const std::array<double, 2> seconds{
            spectral.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
        const ColourErrorSlice e = colour_error(spectral, rgb).front();
        char to1_rgb[64], to1_s[64];
        auto to1 = [](double t, double rse) { return t * rse * rse / 1e-4; };
        std::snprintf(to1_rgb, sizeof to1_rgb, "%.2f/%.2f/%.2f", to1(seconds[1], e.xyz_median_rse_other.x),
                      to1(seconds[1], e.xyz_median_rse_other.y), to1(seconds[1], e.xyz_median_rse_other.z));
        std::snprintf(to1_s, sizeof to1_s, "%.2f/%.2f/%.2f", to1(seconds[0], e.xyz_median_rse_spectral.x),
                      to1(seconds[0], e.xyz_median_rse_spectral.y), to1(seconds[0], e.xyz_median_rse_spectral.z));
        std::printf("%-28s %9.2f %9.2f %-24s %-24s %.2f\n", run.stack.name.c_str(), seconds[1], seconds[0], to1_rgb,
                    to1_s, spectral_cost_at_equal_error({e}, seconds));
        std::fflush(stdout);
    }
    return rc;
}

}   // namespace gonio
