// spectral_simulate.cpp: see spectral_simulate.h.
#include "spectral_simulate.h"
#include "histogram.h"
#include "options.h"
#include "output.h"
#include "spectral_output.h"
#include "stack_spectral.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace gonio {

namespace {

// part's sums into total: the same stack shape, options, angles and bins, another wavelength or seed (the pooled se
// of points at different wavelengths is an upper bound: their means differ)
void add_run(SimResult& total, const SimResult& part) {
    total.options.paths += part.options.paths;
    for (size_t a = 0; a < total.angles.size(); ++a) {
        AngleResult& t = total.angles[a];
        const AngleResult& p = part.angles[a];
        t.paths += p.paths;
        for (size_t i = 0; i < t.raw.size(); ++i) t.raw[i] += p.raw[i];
        for (size_t k = 0; k < kEnergyEntries; ++k) t.energy[k] += p.energy[k];
        t.seconds += p.seconds;
        t.device_seconds += p.device_seconds;
    }
}

// One pass of three bands from three runs of one wavelength each (a dispersive stack): channel c of the pass is
// channel c of runs[c] (every channel of a run is at its one wavelength).
SimResult channels_of(const std::array<SimResult, 3>& runs) {
    SimResult out = runs[0];
    for (size_t a = 0; a < out.angles.size(); ++a) {
        AngleResult& t = out.angles[a];
        for (int c = 1; c < 3; ++c) {
            const AngleResult& p = runs[size_t(c)].angles[a];
            if (p.paths != t.paths) throw std::logic_error("channels_of: the runs differ in paths");
            for (size_t i = 0; i < t.raw.size(); i += 6) {   // per bin: sum w (RGB), sum w^2 (RGB)
                t.raw[i + size_t(c)] = p.raw[i + size_t(c)];
                t.raw[i + 3 + size_t(c)] = p.raw[i + 3 + size_t(c)];
            }
            for (size_t e = 0; e < kEnergyEntries; e += 3) t.energy[e + size_t(c)] = p.energy[e + size_t(c)];
            t.seconds += p.seconds;
            t.device_seconds += p.device_seconds;
        }
    }
    return out;
}

}   // namespace

SpectralResult trace_spectral(const SimulateRun& run, const SpectralBands& bands, VkContext* ctx, unsigned threads,
                              int& rc) {
    if (run.previous) usage_error("--spectral does not resume a run yet (--resume)");
    if (const std::string why =
            spectral_refusal(run.stack, bands.point_nm(0, 0), bands.point_nm(bands.count() - 1, bands.points - 1));
        !why.empty())
        usage_error(run.stack.source_path + ": --spectral: " + why);
    const size_t n_bands = bands.count(), passes = (n_bands + 2) / 3;
    SpectralResult r{run.stack, bands, {}, 0};
    const std::vector<double> share = pass_shares(bands);
    const auto start = std::chrono::steady_clock::now();
    // a dispersive stack: one wavelength per run, three runs to a pass (each run's three channels alike)
    const bool disperses = stack_disperses(run.stack);
    if (disperses && run.sim.rse_target > 0)
        usage_error(run.stack.source_path +
                    ": --spectral with a dispersive IOR traces each band on its own, with "
                    "--paths per band: --rse is not taken");
    // the run of pass g's point j at wavelengths nm (one wavelength in every channel where the stack disperses)
    auto trace = [&](size_t g, unsigned j, uint32_t seed, const std::array<double, 3>& nm, uint64_t paths) {
        SimOptions opt = run.sim;
        opt.seed = seed;
        opt.paths = paths;
        opt.on_checkpoint = nullptr;   // a spectral run keeps no state file (no --resume yet)
        opt.checkpoint_seconds = 0;
        if (opt.progress)
            std::fprintf(stderr, "gonio: --spectral pass %zu/%zu (point %u): %g, %g, %g nm, %llu paths per angle\n",
                         g + 1, passes, j + 1, nm[0], nm[1], nm[2], (unsigned long long)opt.paths);
        SimResult part = ctx ? simulate_gpu(*ctx, stack_at_wavelengths(run.stack, nm), opt)
                             : simulate_cpu(stack_at_wavelengths(run.stack, nm), opt, threads);
        for (size_t a = 0; a < part.angles.size(); ++a)
            if (energy_book(part, a).invalid != glm::dvec3(0)) rc = 1;
        return part;
    };
    for (size_t g = 0; g < passes; ++g) {
        const uint64_t pass_paths = std::max<uint64_t>(1, uint64_t(std::ceil(double(run.sim.paths) * share[g])));
        const uint64_t point_paths = (pass_paths + bands.points - 1) / bands.points;
        for (unsigned j = 0; j < bands.points; ++j) {
            std::array<double, 3> nm{};
            for (size_t c = 0; c < 3; ++c) nm[c] = bands.point_nm(std::min(3 * g + c, n_bands - 1), j);
            const uint32_t seed = run.sim.seed + uint32_t(g + passes * j);   // every pass and point its own
            SimResult part;
            if (disperses) {
                std::array<SimResult, 3> runs;
                for (size_t c = 0; c < 3; ++c)   // seeds beyond every non-dispersive pass's
                    runs[c] = trace(g, j, seed + uint32_t(passes * bands.points * (c + 1)), {nm[c], nm[c], nm[c]},
                                    point_paths);
                part = channels_of(runs);
            } else {
                part = trace(g, j, seed, nm, point_paths);
            }
            if (j == 0)
                r.groups.push_back(std::move(part));
            else
                add_run(r.groups.back(), part);
        }
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

int run_spectral_simulate(const SimulateRun& run, const SpectralBands& bands, VkContext* ctx, unsigned threads) {
    int rc = 0;
    const SpectralResult r = trace_spectral(run, bands, ctx, threads, rc);
    const size_t n_bands = bands.count(), passes = r.groups.size();
    const std::string exr = run.out + "/" + safe_file_name(run.stack.name) + ".exr";
    write_spectral_exr(exr, r);
    write_spectral_summary(run.out + "/summary.json", r);
    const std::vector<std::array<double, 3>> w = xyz_weights(bands);
    for (size_t a = 0; a < r.groups.front().angles.size(); ++a) {
        glm::dvec3 xyz(0);
        for (size_t b = 0; b < n_bands; ++b)
            xyz += glm::dvec3(w[b][0], w[b][1], w[b][2]) * energy_book(r.groups[b / 3], a).reflected[int(b % 3)];
        const std::array<double, 3> rgb = xyz_to_linear_srgb({xyz.x, xyz.y, xyz.z});
        std::printf("theta_i %g: reflected XYZ %.4f %.4f %.4f, linear sRGB %.4f %.4f %.4f (%zu bands of %g nm)\n",
                    r.groups.front().angles[a].theta_i_deg, xyz.x, xyz.y, xyz.z, rgb[0], rgb[1], rgb[2], n_bands,
                    bands.width_nm);
    }
    std::printf("wrote %s and %s/summary.json (%zu passes, %.1f s)\n", exr.c_str(), run.out.c_str(), passes, r.seconds);
    return rc;
}

}   // namespace gonio
