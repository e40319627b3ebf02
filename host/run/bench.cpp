// bench.cpp: see bench.h. `gonio bench`: paths per second of the reference (device, general walk, CPU twin), a table of
// incident angles side by side against one at a time, and with
// --out: the reference's convergence, what each model costs against how far it is from the reference (Pareto),
// and an error atlas over random two-layer stacks (which model is best where).
#include "bench.h"
#include "render_case.h"
#include "model_render.h"
#include "reference_render.h"
#include "python_tool.h"
#include "stack_gpu.h"
#include "comparison.h"
#include "user_model.h"
#include "histogram.h"
#include "json.h"
#include "random_stack.h"
#include "spectral_bench.h"
#include "stack.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sys/resource.h>
#include <thread>

namespace fs = std::filesystem;

namespace gonio {

namespace {

// bench.json's numbers: 6 significant digits; not finite (a model without a cost, no runner-up): null.
Json num(double v) { return json_rounded(v, 6); }

double process_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double remap(double f) { return std::log1p(std::sqrt(std::max(f, 0.0))); }

// Reference convergence for one stack: runs of 2^16 .. 2^23 paths against a 2^25-path run of another seed
// (returned in `truth`). Per run: relative RMS error against the long run and the median relative standard
// error over the bins above 1% of their slice's peak; the RMS difference in the seeds' remapped space
// log(1 + sqrt f) over all bins (the metric the models are judged by); paths, wall and device seconds.
// The fit: median rse = c / sqrt(N) (c by least squares in log space over the runs of 2^18 paths and more,
// where every counted bin holds enough paths), and the free slope of the same regression as a check.
struct Convergence {
    Json json = Json::array();
    SimResult truth;
    double c = 0, slope = 0;
};

Convergence convergence(VkContext& ctx, const Stack& s, SimOptions o) {
    Convergence cv;
    o.progress = false;
    o.seed = 1000;
    o.paths = 1u << 25;
    cv.truth = simulate_gpu(ctx, s, o);
    Slice t = make_slice(cv.truth, 0, kReflection);
    double sx = 0, sy = 0, sxx = 0, sxy = 0, sc = 0;
    int nfit = 0;
    for (int k = 16; k <= 23; ++k) {
        o.seed = uint32_t(k);
        o.paths = 1ull << k;
        SimResult r = simulate_gpu(ctx, s, o);
        Slice sl = make_slice(r, 0, kReflection);
        double se2 = 0, rm2 = 0;
        std::vector<double> rse;
        int n = 0;
        for (int c = 0; c < kChannels; ++c) {
            double peak = 0;
            for (auto& v : t.f) peak = std::max(peak, v[c]);
            for (size_t b = 0; b < t.f.size(); ++b) {
                double d_remap = remap(sl.f[b][c]) - remap(t.f[b][c]);
                rm2 += d_remap * d_remap;
                if (!(t.f[b][c] > 0.01 * peak)) continue;
                double d = (sl.f[b][c] - t.f[b][c]) / t.f[b][c];
                se2 += d * d;
                n++;
                rse.push_back(sl.f[b][c] > 0 ? sl.se[b][c] / sl.f[b][c] : 1.0);
            }
        }
        std::nth_element(rse.begin(), rse.begin() + rse.size() / 2, rse.end());
        double med = rse.empty() ? 0.0 : rse[rse.size() / 2];
        if (k >= 18 && med > 0) {
            double x = std::log(double(o.paths)), y = std::log(med);
            sx += x;
            sy += y;
            sxx += x * x;
            sxy += x * y;
            sc += y + 0.5 * x;
            nfit++;
        }
        cv.json.push_back({{"paths", o.paths},
                           {"seconds", num(r.angles[0].seconds)},
                           {"device_seconds", num(r.angles[0].device_seconds)},
                           {"relative_rmse", num(std::sqrt(se2 / std::max(n, 1)))},
                           {"median_rse", num(med)},
                           {"rmse_remapped", num(std::sqrt(rm2 / double(3 * t.f.size())))}});
    }
    if (nfit >= 2) {
        cv.c = std::exp(sc / nfit);
        cv.slope = (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx);
    }
    return cv;
}

// A full isotropic table of incident angles (0 to 88 degrees every 2) traced two ways with the same paths in total as
// a throughput run: every angle side by side in one dispatch sequence (simulate_gpu's default) and one angle after
// the other (angles_per_dispatch 1), the same bytes either way. Wall seconds of whole simulate_gpu calls, in the order
// in turn, side by side, side by side, in turn, so that a steady drift of the machine's speed cancels in the ratio.
struct AngleTable {
    size_t angles = 0;
    uint64_t paths_per_angle = 0;
    double side_by_side = 0, in_turn = 0;   // wall seconds, sums of two runs each
    double side_by_side_cpu = 0, in_turn_cpu = 0;   // this process's CPU seconds (steadier on a shared machine)
};

AngleTable angle_table(VkContext& ctx, const Stack& s, const SimOptions& sim) {
    AngleTable t;
    SimOptions o = sim;
    o.theta_i_deg.clear();
    for (int deg = 0; deg <= 88; deg += 2) o.theta_i_deg.push_back(deg);
    t.angles = o.theta_i_deg.size();
    o.paths = t.paths_per_angle = std::max<uint64_t>(sim.paths / t.angles, 1);
    for (uint32_t per_dispatch : {1u, 0u, 0u, 1u}) {
        o.angles_per_dispatch = per_dispatch;
        auto t0 = std::chrono::steady_clock::now();
        const double c0 = process_cpu_seconds();
        simulate_gpu(ctx, s, o);
        (per_dispatch == 1 ? t.in_turn_cpu : t.side_by_side_cpu) += process_cpu_seconds() - c0;
        (per_dispatch == 1 ? t.in_turn : t.side_by_side) +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    return t;
}

// gonio render's stages on one stack (docs/RENDER.md): the 0:88:2 table in two halves (the angle table's paths per
// angle in all), the reference's sum on the CPU, and every model that represents the stack on the device (each
// model's dispatches with their first-dispatch JIT; the pipelines, created concurrently, apart): the models --models
// selects (by default the models as published, with the --model files).
Json render_stage(VkContext& ctx, const Stack& s, const SimOptions& sim, const Environment& env, uint32_t size,
                  const ModelOptions& selected) {
    SphereStageRequest r;
    r.stack = &s;
    r.environment = &env;
    r.table_half = sim;
    r.table_half.theta_i_deg = RenderRequest::default_table_angles();
    r.table_half.paths = std::max<uint64_t>(sim.paths / r.table_half.theta_i_deg.size() / 2, 1000);
    r.models.size = size;
    r.models.models = selected;
    r.quiet = true;
    const SphereStage stage = render_sphere_stage(ctx, r);
    const SimOptions& o = r.table_half;
    const ModelRenderOptions& mo = r.models;
    const ReferenceRender& ref = stage.reference;
    const ModelRenderStage& st = stage.model_stage;
    const double table_seconds = stage.table_seconds;
    Json per = Json::array();
    std::string line;
    size_t rendered = 0;
    for (const ModelRender& m : stage.models) {
        if (!m.not_applicable.empty()) continue;
        ++rendered;
        per.push_back({{"id", m.id}, {"render_seconds", num(m.render_seconds)}});
        char b[96];
        std::snprintf(b, sizeof b, " %s %.2f", m.id.c_str(), m.render_seconds);
        line += b;
    }
    std::printf(
        "%-20s render %ux%u under %s (%ux%u), %u iterations: table %.2f s (2 x 45 angles x %llu paths), reference %.2f "
        "s (CPU, %u threads), %zu models %.2f s (pipelines %.2f s, shared samples %.2f s); per model s:%s\n",
        s.name.c_str(), size, size, env.name.c_str(), env.width, env.height, mo.spp, table_seconds,
        (unsigned long long)o.paths, ref.seconds, ref.threads, rendered, st.wall_seconds, st.pipelines_seconds,
        st.samples_seconds, line.c_str());
    return {{"size", size},
            {"environment", env.name + " (" + env.source + ")"},
            {"environment_texels", {env.width, env.height}},
            {"iterations_per_pixel", mo.spp},
            {"table_seconds", num(table_seconds)},
            {"table_paths_per_angle_per_half", o.paths},
            {"reference_seconds", num(ref.seconds)},
            {"reference_threads", ref.threads},
            {"models_rendered", rendered},
            {"models_wall_seconds", num(st.wall_seconds)},
            {"models_pipelines_seconds", num(st.pipelines_seconds)},
            {"models_samples_seconds", num(st.samples_seconds)},
            {"models", per}};
}

struct ModelPoint {
    std::string id, reason;
    double rmse = NAN, rmse_t = NAN, noise = NAN, ns_per_eval = NAN, grid_seconds = NAN;
    uint64_t evaluations = 0;
};

// Each model on the truth run's grid (one incident angle, the default bins): device cost and error. A first
// evaluation on a tiny grid compiles the pipelines and computes Belcour's tables, so the timed ones are the
// models alone; of three timed evaluations each model keeps its least device time (other load on a shared
// machine only ever adds to it).
std::vector<ModelPoint> model_points(ModelEvaluator& ev, const SimResult& truth, const ModelOptions& mo) {
    ModelGrid g = model_grid(truth);
    ModelGrid tiny{3, 6, 30.0, 60.0, g.theta_i_deg};
    ev.evaluate(truth.stack, tiny, nullptr, mo);
    std::vector<ModelCost> costs;
    std::vector<ModelSlices> ms = ev.evaluate(truth.stack, g, &costs, mo);
    for (int rep = 0; rep < 2; ++rep) {
        std::vector<ModelCost> again;
        ev.evaluate(truth.stack, g, &again, mo);
        for (size_t m = 0; m < costs.size() && m < again.size(); ++m)
            costs[m].device_seconds = std::min(costs[m].device_seconds, again[m].device_seconds);
    }
    const Comparison cmp = compare_models(truth, ms);
    std::vector<ModelPoint> pts;
    for (size_t m = 0; m < ms.size(); ++m) {
        ModelPoint p;
        p.id = ms[m].id;
        p.reason = ms[m].not_applicable.empty() ? ms[m].invalid : ms[m].not_applicable;
        if (p.reason.empty()) {
            const ModelMetrics& mm = cmp.models[m].r[0];
            p.rmse = mm.rmse_remapped;
            p.noise = mm.reference_noise_remapped;
            if (!cmp.models[m].t.empty()) p.rmse_t = cmp.models[m].t[0].rmse_remapped;
            p.evaluations = costs[m].evaluations;
            p.grid_seconds = costs[m].device_seconds;
            p.ns_per_eval = costs[m].evaluations ? costs[m].device_seconds * 1e9 / double(costs[m].evaluations) : NAN;
        }
        pts.push_back(p);
    }
    return pts;
}

Json model_points_json(const std::vector<ModelPoint>& pts) {
    Json j = Json::array();
    for (const ModelPoint& p : pts) {
        if (!p.reason.empty())
            j.push_back({{"id", p.id}, {"applicable", false}, {"reason", p.reason}});
        else
            j.push_back({{"id", p.id},
                         {"applicable", true},
                         {"rmse_remapped", num(p.rmse)},
                         {"rmse_remapped_transmission", num(p.rmse_t)},
                         {"reference_noise_remapped", num(p.noise)},
                         {"evaluations", p.evaluations},
                         {"device_seconds_per_grid", num(p.grid_seconds)},
                         {"ns_per_evaluation", num(p.ns_per_eval)}});
    }
    return j;
}

// The error atlas: random two-layer stacks (a dielectric coat over a conductor: every model applies; coat optical
// depth at most 1, air above), the
// reference at 0/30/60/80 degrees on 2 x 4 degree bins, every model on the same bins; per stack and angle,
// each model's RMSE in log(1 + sqrt f), the reference's own noise, the best model and its margin over the
// runner-up.
Json atlas_json(VkContext& ctx, ModelEvaluator& ev, const BenchOptions& b) {
    RandomStackOptions ro;
    ro.min_layers = ro.max_layers = 2;
    ro.lambertian_base = false;
    ro.transmissive = false;
    ro.exterior_other_than_air = false;
    ro.max_optical_depth = 1.0;   // coats from clear to moderately absorbing (at 50 every model is the top reflection)
    ro.microsurfaces = false;   // GGX, height-correlated Smith, single scattering: what every model assumes
    SimOptions o;
    o.theta_i_deg = {0, 30, 60, 80};
    o.paths = b.atlas_paths;
    o.seed = b.sim.seed;
    o.dtheta_deg = 2;
    o.dphi_deg = 4;
    Json j = {{"seed", b.sim.seed}, {"paths", o.paths},           {"dtheta", 2},
              {"dphi", 4},          {"theta_i", {0, 30, 60, 80}}, {"stacks", Json::array()}};
    auto t0 = std::chrono::steady_clock::now();
    for (uint32_t i = 0; i < b.atlas_stacks; ++i) {
        Stack s = random_stack(b.sim.seed, i, ro);
        SimResult ref = simulate_gpu(ctx, s, o);
        std::vector<ModelSlices> ms = ev.evaluate(s, model_grid(ref), nullptr, b.models);
        const Comparison cmp = compare_models(ref, ms);
        const Layer &coat = s.layers[0], &base = s.layers[1];
        Json entry = {
            {"name", s.name},
            {"coat_roughness", num(coat.roughness)},
            {"coat_ior", num(coat.ior.x)},
            {"coat_optical_depth", num((coat.optical_depth.x + coat.optical_depth.y + coat.optical_depth.z) / 3)},
            {"base_roughness", num(base.roughness)},
            {"base_ior", num((base.ior.x + base.ior.y + base.ior.z) / 3)},
            {"base_k", num((base.k.x + base.k.y + base.k.z) / 3)},
            {"angles", Json::array()}};
        for (size_t a = 0; a < o.theta_i_deg.size(); ++a) {
            std::string best;
            Json rm = Json::object();
            double b1 = INFINITY, b2 = INFINITY, noise = 0;
            for (size_t k = 0; k < ms.size(); ++k) {
                const ModelSlices& m = ms[k];
                if (!model_has_bins(m)) continue;
                const ModelMetrics& mm = cmp.models[k].r[a];
                noise = mm.reference_noise_remapped;
                rm[m.id] = num(mm.rmse_remapped);
                if (mm.rmse_remapped < b1) {
                    b2 = b1;
                    b1 = mm.rmse_remapped;
                    best = m.id;
                } else if (mm.rmse_remapped < b2)
                    b2 = mm.rmse_remapped;
            }
            entry["angles"].push_back({{"theta_i", num(o.theta_i_deg[a])},
                                       {"best", best},
                                       {"best_rmse", num(b1)},
                                       {"margin", num(b2 - b1)},
                                       {"reference_noise_remapped", num(noise)},
                                       {"rmse_remapped", rm}});
        }
        j["stacks"].push_back(entry);
        std::printf("atlas %u/%u: %s (coat alpha %g, base alpha %g)\n", i + 1, b.atlas_stacks, s.name.c_str(),
                    coat.roughness, base.roughness);
        std::fflush(stdout);
    }
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    j["seconds"] = num(secs);
    return j;
}

// The booking estimators (docs/PHYSICS.md, "Booking estimators") against the analog walk (--no-branching), where they
// apply: paths per second, the median relative standard error at the run's paths and the seconds to a 1% median
// rse, N (rse / 0.01)^2 / (paths per second), each the mean of two runs alternated (analog, estimators, estimators,
// analog) so that a steady drift of the machine cancels in the ratio. Printed, and as bench.json's entry.
Json booking_entry(VkContext& ctx, const Stack& s, const SimOptions& sim) {
    const WalkSpec ws = walk_spec(s, true);
    if (!ws.entry_branch && ws.exit_estimates == 0) return Json();
    double pps[2] = {0, 0}, rse[2] = {0, 0};
    for (int run = 0; run < 4; ++run) {
        const int k = (run == 1 || run == 2) ? 1 : 0;   // 0: the analog walk, 1: the estimators
        SimOptions o = sim;
        o.branching = k == 1;
        if (run < 2) {   // JIT compile (lavapipe compiles at first dispatch)
            SimOptions warm = o;
            warm.paths = 65536;
            simulate_gpu(ctx, s, warm);
        }
        const SimResult g = simulate_gpu(ctx, s, o);
        pps[k] += 0.5 * double(g.angles[0].paths) / g.angles[0].seconds;
        rse[k] += 0.5 * g.angles[0].median_rse;
    }
    auto to_1pct = [&](int k) { return double(sim.paths) * (rse[k] / 0.01) * (rse[k] / 0.01) / pps[k]; };
    std::printf(
        "%-20s booking estimators %.2f Mpaths/s, median rse %.4f, %.3g s to 1%%; the analog walk (--no-branching) "
        "%.2f Mpaths/s, %.4f, %.3g s: %.2fx sooner\n",
        s.name.c_str(), pps[1] * 1e-6, rse[1], to_1pct(1), pps[0] * 1e-6, rse[0], to_1pct(0), to_1pct(0) / to_1pct(1));
    return {{"paths_per_second", num(pps[1])},
            {"median_rse", num(rse[1])},
            {"seconds_to_rse_1pct", num(to_1pct(1))},
            {"analog_paths_per_second", num(pps[0])},
            {"analog_median_rse", num(rse[0])},
            {"analog_seconds_to_rse_1pct", num(to_1pct(0))},
            {"estimators_over_analog_to_rse_1pct", num(to_1pct(0) / to_1pct(1))}};
}

// One stack's row of the throughput table: the specialised walk, the general walk and the CPU twin, the Lambertian
// series against every trip, the angle table side by side against one angle at a time. Printed, and as bench.json's
// entry; `dev`: the specialised walk's paths per second.
Json throughput_entry(VkContext& ctx, const Stack& s, const SimOptions& sim, const BenchOptions& b, unsigned threads,
                      double& dev) {
    auto timed = [&](bool specialised, double& cpu_per_mpath, bool series = true) {
        SimOptions o = sim;
        o.specialised = specialised;
        o.series = series;
        SimOptions warm = o;
        warm.paths = 65536;
        simulate_gpu(ctx, s, warm);   // JIT compile (lavapipe compiles at first dispatch)
        double c0 = process_cpu_seconds();
        SimResult g = simulate_gpu(ctx, s, o);
        cpu_per_mpath = (process_cpu_seconds() - c0) / (double(o.paths) * 1e-6);
        return double(g.angles[0].paths) / g.angles[0].seconds;
    };
    double dev_cpu = 0, gen_cpu = 0, twin_cpu = 0;
    dev = timed(true, dev_cpu);
    double gen = timed(false, gen_cpu);
    SimOptions c = sim;
    c.paths = b.cpu_paths;
    double c0 = process_cpu_seconds();
    SimResult cpu = simulate_cpu(s, c, threads);
    twin_cpu = (process_cpu_seconds() - c0) / (double(c.paths) * 1e-6);
    double twin = double(cpu.angles[0].paths) / cpu.angles[0].seconds;
    // events per path (interface events and medium collisions), over 2^16 paths of the same walk
    const double events = mean_events_per_path(s, sim, 65536);
    std::printf("%-20s %12.2f %12.3f %12.2f %12.2f %12.3f %8.1fx %8.2fx %12.2f\n", s.name.c_str(), dev * 1e-6, dev_cpu,
                gen * 1e-6, twin * 1e-6, twin_cpu, dev / twin, dev / gen, events);
    // the Lambertian series against tracing every trip, the same specialised walk otherwise (docs/PHYSICS.md)
    Json series_json;
    if (walk_spec(s, true).series) {
        double full_cpu = 0;
        double full = timed(true, full_cpu, false);
        std::printf(
            "%-20s Lambertian series %.2f Mpaths/s (%.3f cpu-s/Mpath); every trip traced (--no-series) %.2f "
            "(%.3f): %.2fx\n",
            s.name.c_str(), dev * 1e-6, dev_cpu, full * 1e-6, full_cpu, dev / full);
        series_json = {{"every_trip_paths_per_second", num(full)},
                       {"every_trip_cpu_seconds_per_mpath", num(full_cpu)},
                       {"series_over_every_trip", num(dev / full)}};
    }
    const Json booking = booking_entry(ctx, s, sim);
    const AngleTable at = angle_table(ctx, s, sim);
    std::printf(
        "%-20s angle table 0:88:2 (%zu angles x %llu paths): side by side %.3f s (%.3f cpu-s), one angle at a "
        "time %.3f s (%.3f cpu-s): %.2fx (cpu %.2fx)\n",
        s.name.c_str(), at.angles, (unsigned long long)at.paths_per_angle, at.side_by_side / 2, at.side_by_side_cpu / 2,
        at.in_turn / 2, at.in_turn_cpu / 2, at.in_turn / at.side_by_side, at.in_turn_cpu / at.side_by_side_cpu);
    std::fflush(stdout);
    Json entry = {{"stack", s.name},
                  {"layers", s.layers.size()},
                  {"paths_per_second", num(dev)},
                  {"cpu_seconds_per_mpath", num(dev_cpu)},
                  {"general_walk_paths_per_second", num(gen)},
                  {"general_walk_cpu_seconds_per_mpath", num(gen_cpu)},
                  {"specialised_over_general", num(dev / gen)},
                  {"cpu_twin_paths_per_second", num(twin)},
                  {"cpu_twin_cpu_seconds_per_mpath", num(twin_cpu)},
                  {"device_over_cpu_twin", num(dev / twin)},
                  {"events_per_path", num(events)},
                  {"lambertian_series", series_json},
                  {"booking_estimators", booking},
                  {"angle_table",
                   {{"angles", at.angles},
                    {"paths_per_angle", at.paths_per_angle},
                    {"side_by_side_seconds", num(at.side_by_side / 2)},
                    {"one_angle_at_a_time_seconds", num(at.in_turn / 2)},
                    {"side_by_side_cpu_seconds", num(at.side_by_side_cpu / 2)},
                    {"one_angle_at_a_time_cpu_seconds", num(at.in_turn_cpu / 2)},
                    {"side_by_side_speedup", num(at.in_turn / at.side_by_side)},
                    {"side_by_side_cpu_speedup", num(at.in_turn_cpu / at.side_by_side_cpu)}}}};
    return entry;
}

// bench --out, per stack: the reference's convergence, its 1/sqrt(N) fit, and each model's cost against its error
// on the converged run's bins; `dev`: the device's paths per second measured for the stack.
void add_convergence(Json& entry, VkContext& ctx, ModelEvaluator& evaluator, const Stack& s, const SimOptions& sim,
                     const BenchOptions& b, double dev) {
    Convergence cv = convergence(ctx, s, sim);
    entry["convergence"] = cv.json;
    if (cv.c > 0) {
        double n1 = std::pow(cv.c / 0.01, 2), n01 = std::pow(cv.c / 0.001, 2);
        entry["rse_fit"] = {{"method",
                             "median rse = c / sqrt(N), c fitted in log space on the runs of 2^18 to 2^23 "
                             "paths; seconds = N / the device paths per second measured above"},
                            {"c", num(cv.c)},
                            {"free_slope", num(cv.slope)},
                            {"paths_to_rse_1pct", num(n1)},
                            {"paths_to_rse_0_1pct", num(n01)},
                            {"seconds_to_rse_1pct", num(n1 / dev)},
                            {"seconds_to_rse_0_1pct", num(n01 / dev)}};
        std::printf(
            "%-20s median relative standard error 1%% after %.3g paths (%.3g s), 0.1%% after %.3g paths (%.3g s) "
            "(fit c/sqrt(N), free slope %.3f)\n",
            s.name.c_str(), n1, n1 / dev, n01, n01 / dev, cv.slope);
    }
    std::vector<ModelPoint> pts = model_points(evaluator, cv.truth, b.models);
    entry["models"] = model_points_json(pts);
    for (auto& p : pts)
        if (p.reason.empty())
            std::printf("%-20s   %-20s rmse %.4f (reference noise %.4f)  %6.1f ns/evaluation  %.4f device-s per grid\n",
                        s.name.c_str(), p.id.c_str(), p.rmse, p.noise, p.ns_per_eval, p.grid_seconds);
    std::fflush(stdout);
}

}   // namespace

// Prints the throughput table; with `out`, also measures the reference's convergence, the models' cost and
// error (Pareto), the error atlas, and writes DIR/bench.json, the figures and DIR/bench.html. Returns the
// process exit status (3 if the validation layer reported anything).
int run_bench(const BenchOptions& b) {
    std::vector<std::string> files = b.stacks;
    if (files.empty()) {
        if (fs::is_directory("stacks"))
            for (auto& e : fs::directory_iterator("stacks"))
                if (e.path().extension() == ".toml") files.push_back(e.path().string());
        std::sort(files.begin(), files.end());
    }
    if (files.empty()) throw std::invalid_argument("bench: no stack files (run from the repository root or name them)");
    if (b.sim.theta_i_deg.size() != 1) throw std::invalid_argument("bench takes one --theta-i");
    SimOptions sim = b.sim;
    sim.progress = false;
    validate_options(sim);
    VkContext ctx(b.ctx);
    ModelEvaluator evaluator(ctx);
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    Json json = {{"device", ctx.device_info().name},
                 {"driver", ctx.driver_string()},
                 {"cpu_threads", threads},
                 {"theta_i", num(sim.theta_i_deg[0])},
                 {"paths", sim.paths},
                 {"cpu_paths", b.cpu_paths},
                 {"stacks", Json::array()}};
    std::printf("gonio bench: device %s (%s); CPU twin on %u threads; theta_i %g; %llu device paths, %llu CPU paths\n",
                ctx.device_info().name.c_str(), ctx.driver_string().c_str(), threads, sim.theta_i_deg[0],
                (unsigned long long)sim.paths, (unsigned long long)b.cpu_paths);
    std::printf(
        "Mpaths/s are wall-clock; 'cpu-s/Mpath' is this process's CPU time (all threads) per million paths,\n"
        "which other load on the machine does not inflate. The first dispatch's JIT compile is excluded.\n");
    std::printf("%-20s %12s %12s %12s %12s %12s %9s %9s %12s\n", "stack", "device", "cpu-s/Mpath", "general",
                "CPU twin", "cpu-s/Mpath", "dev/twin", "spec/gen", "events/path");
    std::optional<Environment> env;
    if (!b.render_env.empty()) env = load_render_environment(b.render_env);
    for (auto& f : files) {
        Stack s = parse_stack_file(f);
        double dev = 0;
        Json entry = throughput_entry(ctx, s, sim, b, threads, dev);
        if (env) entry["render"] = render_stage(ctx, s, sim, *env, b.render_size, b.models);
        std::fflush(stdout);
        if (b.out.empty())
            entry["convergence"] = nullptr;
        else
            add_convergence(entry, ctx, evaluator, s, sim, b, dev);
        json["stacks"].push_back(entry);
    }
    if (!b.out.empty()) {
        json["belcour_table_device_seconds"] = num(evaluator.table_seconds());
        if (b.atlas_stacks > 0) json["atlas"] = atlas_json(ctx, evaluator, b);
    }
    if (!b.out.empty()) {
        fs::create_directories(b.out);
        write_json_file(b.out + "/bench.json", json);
        std::printf("wrote %s/bench.json\n", b.out.c_str());
        run_python_tool("bench_plot.py", b.out, "convergence.png, pareto.png, atlas.png and bench.html");
    }
    if (ctx.validation_messages() > 0) {
        std::fprintf(stderr, "gonio: %llu Vulkan validation message(s): failing\n",
                     (unsigned long long)ctx.validation_messages());
        return 3;
    }
    return 0;
}

}   // namespace gonio
