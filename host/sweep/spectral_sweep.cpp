// spectral_sweep.cpp: see spectral_sweep.h.
#include "spectral_sweep.h"
#include "colour_error.h"
#include "histogram.h"
#include "model_evaluator.h"
#include "output.h"
#include "spectral_compare.h"
#include "spectral_simulate.h"
#include "stack_spectral.h"
#include "text_format.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace gonio {

namespace {

std::string num(double v) { return format_g9(v); }

// One row's fields after the configuration's prefix: the slice's angle, side, the colours' id and how they were
// evaluated, then its colour error (kSpectralSweepColumns).
std::string colour_row(const ColourErrorSlice& e, const std::string& id, const std::string& evaluated, uint64_t paths) {
    const glm::dvec3 &m = e.albedo_other, &r = e.albedo_spectral;
    return num(e.theta_i_deg) + "," + (e.side ? "T" : "R") + "," + id + "," + evaluated + "," + num(m.x) + "," +
           num(m.y) + "," + num(m.z) + "," + num(r.x) + "," + num(r.y) + "," + num(r.z) + "," +
           num(e.albedo_de.de2000) + "," + num(e.albedo_de.de_itp) + "," + std::to_string(e.lit) + "," +
           num(e.median_de2000) + "," + num(e.p95_de2000) + "," + num(e.max_de2000) + "," + num(e.median_de_itp) + "," +
           num(e.p95_de_itp) + "," + num(e.median_de2000_noise) + "," + std::to_string(paths);
}

// Every pass's paths at the incident angle theta_i: the spectral run's paths there.
uint64_t spectral_paths(const SpectralResult& r, double theta_i_deg) {
    uint64_t n = 0;
    for (const SimResult& g : r.groups)
        for (const AngleResult& a : g.angles)
            if (a.theta_i_deg == theta_i_deg) n += a.paths;
    return n;
}

// Configuration i's rows: the models, the RGB run and the reference, per angle and side.
std::string spectral_config_rows(VkContext& ctx, ModelEvaluator& evaluator, const Sweep& s, uint64_t i,
                                 const SweepRunOptions& o, const std::string& keep_dir) {
    const Stack stack = s.stack(i);
    SimOptions so = sweep_sim_options(s, true);
    so.seed = s.config_seed(i);
    validate_options(so);
    int rc = 0;
    const SpectralResult spectral = trace_spectral(Case{stack, so, "", std::nullopt}, s.spectral.bands, &ctx, 1, rc);
    if (rc != 0)
        throw std::runtime_error("configuration " + std::to_string(i) +
                                 ": paths booked a number that is not finite: a bug, please report it with the sweep");
    std::string clipped;
    const std::vector<SpectralModelColours> models =
        spectral_model_colours(spectral, stack, o.models, s.spectral.reduction, evaluator, false, clipped);
    // the RGB run: the stack reduced to three channels, its own seed (beyond the spectral passes')
    SimOptions ro = so;
    ro.seed = so.seed + 0x9e3779b9u;
    const SimResult rgb = simulate_gpu(ctx, stack_reduced_to_rgb(stack, s.spectral.reduction, clipped), ro);
    const std::vector<ColourErrorSlice> rgb_error = colour_error(spectral, rgb);
    if (!keep_dir.empty()) {
        std::filesystem::create_directories(keep_dir);
        write_spectral_exr(keep_dir + "/" + safe_file_name(stack.name) + ".exr", spectral);
        write_spectral_summary(keep_dir + "/summary.json", spectral);
    }
    const std::string prefix = config_prefix(s, i) + ",";
    const std::string in_rgb = std::string("rgb-reduced-") + to_string(s.spectral.reduction);
    std::string rows;
    for (const SpectralModelColours& m : models) {
        if (!m.why.empty()) {
            std::fprintf(stderr, "gonio: configuration %llu: %s not scored: %s\n", (unsigned long long)i, m.id.c_str(),
                         m.why.c_str());
            continue;
        }
        const std::string how = m.in_rgb ? in_rgb : "band-by-band";
        for (const ColourErrorSlice& e : m.slices)
            rows += prefix + colour_row(e, m.id, how, spectral_paths(spectral, e.theta_i_deg)) + "\n";
    }
    for (const ColourErrorSlice& e : rgb_error)
        rows += prefix + colour_row(e, "rgb-run", in_rgb, spectral_paths(spectral, e.theta_i_deg)) + "\n";
    for (const ColourErrorSlice& e : rgb_error) {   // the reference: its albedo, the colour fields empty
        const glm::dvec3& r = e.albedo_spectral;
        rows += prefix + num(e.theta_i_deg) + "," + (e.side ? "T" : "R") + ",reference,band-by-band,,,," + num(r.x) +
                "," + num(r.y) + "," + num(r.z) + ",,,,,,,,,," +
                std::to_string(spectral_paths(spectral, e.theta_i_deg)) + "\n";
    }
    return rows;
}

}   // namespace

uint64_t run_spectral_sweep(VkContext& ctx, const Sweep& s, const std::string& dir, const SweepRunOptions& o) {
    uint64_t mine = 0;
    const std::vector<uint64_t> todo = sweep_todo(s, dir, o, mine);
    ModelEvaluator evaluator(ctx);
    const auto t0 = std::chrono::steady_clock::now();
    uint64_t computed = 0;
    for (uint64_t i : todo) {
        const auto c0 = std::chrono::steady_clock::now();
        const std::string rows =
            spectral_config_rows(ctx, evaluator, s, i, o, o.keep_results ? config_result_dir(dir, i) : std::string());
        write_config(s, dir, i, rows, std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count());
        ++computed;
        if (o.progress)
            print_sweep_progress(s, o, mine - todo.size() + computed, mine, computed, todo.size() - computed,
                                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    if (o.progress && computed > 0) std::fprintf(stderr, "\n");
    return computed;
}

}   // namespace gonio
