// spectral_simulate.cpp: see spectral_simulate.h.
#include "spectral_simulate.h"
#include "histogram.h"
#include "refusal.h"
#include "output.h"
#include "spectral_output.h"
#include "stack_spectral.h"
#include "statistics.h"

#include <algorithm>
#include <array>
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

// --band-paths measured: a pilot of --paths / kPilotFraction per pass, seeded apart from the passes' own seeds
constexpr uint64_t kPilotFraction = 8;
constexpr uint32_t kPilotSeed = 0x5bd1e995u;

// Per pass and channel (X, Y, Z), the relative variance of one path: over the lit bins (Y above 1% of the slice's
// peak) of every angle and side that every pass reached (se > 0 in each: a pilot leaves dim bins empty, and their
// se 0 is no measure of their noise), the median of paths x (sum over the pass's bands of w_b se_b)^2 / XYZ^2 (its
// bands fully correlated, as spectral_slice counts them): the median, as the cost's median relative error; averaged
// over the slices with such bins. All zero where no bin qualifies (minimax_pass_shares then gives even shares).
std::vector<std::array<double, 3>> pass_relative_variances(const SpectralResult& r) {
    const std::vector<std::array<double, 3>> w = xyz_weights(r.bands);
    const SimResult& first = r.groups.front();
    const size_t passes = r.groups.size(), n_bands = r.bands.count();
    std::vector<std::array<double, 3>> a(passes, std::array<double, 3>{});
    size_t slices = 0;
    for (size_t k = 0; k < first.angles.size(); ++k)
        for (int side = 0; side < int(first.n_sides); ++side) {
            const SpectralSlice s = spectral_slice(r, k, side);
            double peak = 0;
            for (const glm::dvec3& x : s.xyz) peak = std::max(peak, x.y);
            std::vector<std::vector<double>> v(passes * 3);   // [3 g + c]: per bin
            for (size_t i = 0; i < s.xyz.size(); ++i) {
                if (!(s.xyz[i].y > 0.01 * peak) || !(s.xyz[i].x > 0) || !(s.xyz[i].z > 0)) continue;
                std::vector<glm::dvec3> se(passes, glm::dvec3(0));
                for (size_t b = 0; b < n_bands; ++b) se[b / 3] += glm::dvec3(w[b][0], w[b][1], w[b][2]) * s.se[b][i];
                if (std::any_of(se.begin(), se.end(), [](const glm::dvec3& e) { return !(e.y > 0); })) continue;
                for (size_t g = 0; g < passes; ++g)
                    for (int c = 0; c < 3; ++c)
                        v[3 * g + size_t(c)].push_back(double(r.groups[g].angles[k].paths) * se[g][c] * se[g][c] /
                                                       (s.xyz[i][c] * s.xyz[i][c]));
            }
            if (v.front().empty()) continue;
            ++slices;
            for (size_t g = 0; g < passes; ++g)
                for (int c = 0; c < 3; ++c) a[g][size_t(c)] += nearest_rank_quantile(v[3 * g + size_t(c)], 0.5);
        }
    for (std::array<double, 3>& g : a)
        for (double& x : g) x /= double(std::max<size_t>(slices, 1));
    return a;
}

// One run of the walk in a spectral run: pass g's point j at wavelengths nm (where the stack disperses, one
// wavelength in every channel, for channel `channel` of the pass; -1 otherwise), `paths` per angle from `seed`.
struct PlannedRun {
    size_t g;
    unsigned j;
    int channel;
    std::array<double, 3> nm;
    uint32_t seed;
    uint64_t paths;
};

// The runs of pass g with `paths` per angle over its points, the seeds from seed0: every pass, point and channel its
// own (a dispersive stack's channels beyond every non-dispersive run's seeds).
void plan_pass(std::vector<PlannedRun>& plan, const SpectralBands& bands, size_t g, uint64_t paths, uint32_t seed0,
               bool disperses) {
    const size_t n_bands = bands.count(), passes = (n_bands + 2) / 3;
    const uint64_t point_paths = (paths + bands.points - 1) / bands.points;
    for (unsigned j = 0; j < bands.points; ++j) {
        std::array<double, 3> nm{};
        for (size_t c = 0; c < 3; ++c) nm[c] = bands.point_nm(std::min(3 * g + c, n_bands - 1), j);
        const uint32_t seed = seed0 + uint32_t(g + passes * j);
        if (!disperses) {
            plan.push_back({g, j, -1, nm, seed, point_paths});
            continue;
        }
        for (size_t c = 0; c < 3; ++c)
            plan.push_back(
                {g, j, int(c), {nm[c], nm[c], nm[c]}, seed + uint32_t(passes * bands.points * (c + 1)), point_paths});
    }
}

// The planned runs traced with the run's options: on the device side by side, as many as share a kernel in one batch
// (simulate_gpu_batch: one pipeline for every pass, not one each); on the CPU twin one after another.
std::vector<SimResult> trace_runs(const Case& run, const std::vector<PlannedRun>& plan, VkContext* ctx,
                                  unsigned threads, int& rc) {
    SimOptions opt = run.sim;
    opt.on_checkpoint = nullptr;   // a spectral run keeps no state file (no --resume yet)
    opt.checkpoint_seconds = 0;
    std::vector<Stack> stacks;
    for (const PlannedRun& p : plan) stacks.push_back(stack_at_wavelengths(run.stack, p.nm));
    std::vector<SimResult> out(plan.size());
    if (!ctx) {
        for (size_t i = 0; i < plan.size(); ++i) {
            opt.seed = plan[i].seed;
            opt.paths = plan[i].paths;
            out[i] = simulate_cpu(stacks[i], opt, threads);
        }
    } else {
        for (const std::vector<size_t>& group : batch_groups(*ctx, stacks, opt)) {
            std::vector<Stack> s;
            std::vector<uint32_t> seeds;
            std::vector<uint64_t> paths;
            for (size_t i : group) {
                s.push_back(stacks[i]);
                seeds.push_back(plan[i].seed);
                paths.push_back(plan[i].paths);
            }
            if (opt.progress)
                std::fprintf(stderr,
                             "gonio: --spectral: %zu runs of the walk side by side, %llu to %llu paths per angle\n",
                             group.size(), (unsigned long long)*std::min_element(paths.begin(), paths.end()),
                             (unsigned long long)*std::max_element(paths.begin(), paths.end()));
            std::vector<SimResult> res = simulate_gpu_batch(*ctx, s, seeds, opt, paths);
            for (size_t k = 0; k < group.size(); ++k) out[group[k]] = std::move(res[k]);
        }
    }
    for (const SimResult& part : out)
        for (size_t a = 0; a < part.angles.size(); ++a)
            if (energy_book(part, a).invalid != glm::dvec3(0)) rc = 1;
    return out;
}

// The passes from their runs (plan_pass's order): a dispersive pass's three channels from its three runs, a pass's
// points added; a pass the plan has no run of is empty (no angles).
std::vector<SimResult> passes_of(const std::vector<PlannedRun>& plan, std::vector<SimResult>& runs, size_t passes) {
    std::vector<SimResult> out(passes);
    std::vector<bool> started(passes, false);
    for (size_t i = 0; i < plan.size();) {
        SimResult part;
        if (plan[i].channel < 0) {
            part = std::move(runs[i]);
            i += 1;
        } else {
            part = channels_of({std::move(runs[i]), std::move(runs[i + 1]), std::move(runs[i + 2])});
            i += 3;
        }
        const size_t g = plan[i - 1].g;
        if (!started[g])
            out[g] = std::move(part);
        else
            add_run(out[g], part);
        started[g] = true;
    }
    return out;
}

}   // namespace

SpectralResult trace_spectral(const Case& run, const SpectralBands& chosen, VkContext* ctx, unsigned threads, int& rc) {
    SpectralBands bands = chosen;
    bands.pass_paths = pass_paths_for(chosen, run.sim.rse_target);
    if (run.previous) refuse("--spectral does not resume a run yet (--resume)");
    if (const std::string why =
            spectral_refusal(run.stack, bands.point_nm(0, 0), bands.point_nm(bands.count() - 1, bands.points - 1));
        !why.empty())
        refuse(run.stack.source_path + ": --spectral: " + why);
    if (run.sim.max_seconds > 0)
        refuse("--spectral traces its passes side by side: --max-seconds is not taken (give --paths or --rse)");
    const size_t n_bands = bands.count(), passes = (n_bands + 2) / 3;
    SpectralResult r{run.stack, bands, {}, 0};
    const auto start = std::chrono::steady_clock::now();
    // a dispersive stack: one wavelength per run, three runs to a pass (each run's three channels alike)
    const bool disperses = stack_disperses(run.stack);
    if (disperses && run.sim.rse_target > 0)
        refuse(run.stack.source_path +
               ": --spectral with a dispersive IOR traces each band on its own, with "
               "--paths per band: --rse is not taken");
    const bool measured = bands.pass_paths == SpectralBands::PassPaths::Measured;
    if (measured && run.sim.rse_target > 0)
        refuse(
            "--band-paths measured shares --paths between the passes; with --rse each pass runs to its own "
            "error: give one or the other");
    std::vector<double> share = pass_shares(bands);
    uint64_t pilot_paths = 0;
    if (measured) {   // a pilot in every pass, its noise giving the shares; its paths counted in
        pilot_paths = std::max<uint64_t>(1, run.sim.paths / kPilotFraction);
        std::vector<PlannedRun> plan;
        for (size_t g = 0; g < passes; ++g)
            plan_pass(plan, bands, g, pilot_paths, run.sim.seed + kPilotSeed, disperses);
        std::vector<SimResult> runs = trace_runs(run, plan, ctx, threads, rc);
        r.groups = passes_of(plan, runs, passes);
        share = minimax_pass_shares(pass_relative_variances(r), kMeasuredShareFloor);
    }
    std::vector<PlannedRun> plan;
    for (size_t g = 0; g < passes; ++g) {
        const uint64_t pass_paths = std::max<uint64_t>(1, uint64_t(std::ceil(double(run.sim.paths) * share[g])));
        if (pass_paths > pilot_paths) plan_pass(plan, bands, g, pass_paths - pilot_paths, run.sim.seed, disperses);
    }
    std::vector<SimResult> runs = trace_runs(run, plan, ctx, threads, rc);
    std::vector<SimResult> main = passes_of(plan, runs, passes);
    if (!measured)
        r.groups = std::move(main);
    else   // the rest added to the pilot, in the passes that have more than their pilot's paths
        for (size_t g = 0; g < passes; ++g)
            if (!main[g].angles.empty()) add_run(r.groups[g], main[g]);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

int run_spectral_simulate(const Case& run, const SpectralBands& bands, VkContext* ctx, unsigned threads) {
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
