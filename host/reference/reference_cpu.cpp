// reference_cpu.cpp: the same walk as simulate.comp, on the CPU (the twin). Each thread fills a private
// fixed-point histogram; integer sums make the merge order irrelevant.
#include "reference.h"
#include "stack_gpu.h"

#include <chrono>
#include <cmath>
#include <thread>

namespace gonio {

static_assert(ENERGY_ENTRIES == kEnergyEntries, "the energy book's size in bins.glsl and reference.h");

SimResult simulate_cpu(const Stack& stack, const SimOptions& opt, unsigned threads) {
    validate_options(opt);
    validate_stack(stack);
    if (threads == 0) threads = 1;
    SimResult res;
    res.stack = stack;
    res.options = opt;
    res.device = "CPU twin";
    res.driver = std::to_string(threads) + " threads";
    res.n_theta = uint32_t(std::lround(90.0 / opt.dtheta_deg));
    res.n_phi = uint32_t(std::lround(360.0 / opt.dphi_deg));
    res.n_classes = opt.orders ? 3 : 1;
    res.n_sides = stack.transmissive() ? 2 : 1;
    const size_t n_values = size_t(res.n_classes) * res.n_sides * res.n_theta * res.n_phi * 6;
    const WalkSpec ws = walk_spec(stack, opt.specialised, opt.series, opt.orders, opt.max_events);
    const StackGpu sg = pack_walk_stack(stack, ws);   // (its staging scale is unused: the twin sums in 64 bits)
    const float inv_dtheta = float(180.0 / (M_PI * opt.dtheta_deg));
    const float inv_dphi = float(180.0 / (M_PI * opt.dphi_deg));

    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        AngleResult ar;
        ar.theta_i_deg = opt.theta_i_deg[a];
        ar.paths = opt.paths;
        double ti = ar.theta_i_deg * M_PI / 180.0;
        const float sin_ti = float(std::sin(ti)), cos_ti = float(std::cos(ti));
        auto t0 = std::chrono::steady_clock::now();
        std::vector<std::vector<uint64_t>> hists(threads, std::vector<uint64_t>(n_values, 0));
        std::vector<std::array<int64_t, kEnergyEntries>> energies(threads, std::array<int64_t, kEnergyEntries>{});
        std::vector<std::thread> pool;
        for (unsigned t = 0; t < threads; ++t) {
            pool.emplace_back([&, t] {
                CpuWalker walker(sg, ws);
                auto& h = hists[t];
                auto& e = energies[t];
                uint64_t begin = opt.paths * t / threads, end = opt.paths * (t + 1) / threads;
                for (uint64_t i = begin; i < end; ++i) {
                    Rng rng = rng_init(uint32_t(i), uint32_t(i >> 32), opt.seed, uint32_t(a));
                    auto r = walker.trace_path(sin_ti, cos_ti, rng, opt.max_events);
                    if (!walker.path_is_finite(r)) {   // as tally.glsl: the invalid class alone
                        for (int c = 0; c < 3; ++c) e[9 + c] += int64_t(ENERGY_SCALE);
                        continue;
                    }
                    for (int c = 0; c < 3; ++c) {
                        e[c] += to_fixed_energy(r.absorbed[c]);
                        e[3 + c] += to_fixed_energy(r.lost[c]);
                    }
                    if (r.outcome == OUTCOME_TRUNCATED) {
                        for (int c = 0; c < 3; ++c) e[6 + c] += to_fixed_energy(r.weight[c]);
                    } else if (r.outcome != OUTCOME_ENDED) {
                        uint side = r.outcome == OUTCOME_TRANSMITTED ? 1u : 0u;
                        uint cls = opt.orders ? r.order : 0u;
                        size_t idx = size_t(bin_index(r.dir, side, cls, res.n_sides, res.n_theta, res.n_phi, inv_dtheta, inv_dphi)) * 6;
                        // the same dithered quantisation as the device (bins.glsl), without the packing
                        vec4 u0 = rng_next4(rng), u1 = rng_next4(rng);
                        float u[6] = {u0.x, u0.y, u0.z, u0.w, u1.x, u1.y};
                        for (int c = 0; c < 3; ++c) {
                            float wc = r.weight[c];
                            h[idx + c] += to_fixed_dithered(wc, u[2 * c]);
                            h[idx + 3 + c] += to_fixed_dithered(wc * wc, u[2 * c + 1]);
                        }
                    }
                }
            });
        }
        for (auto& th : pool) th.join();
        ar.raw.assign(n_values, 0);
        for (unsigned t = 0; t < threads; ++t) {
            for (size_t i = 0; i < n_values; ++i) ar.raw[i] += hists[t][i];
            for (size_t c = 0; c < kEnergyEntries; ++c) ar.energy[c] += energies[t][c];
        }
        ar.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        res.angles.push_back(std::move(ar));
    }
    return res;
}

}  // namespace gonio
