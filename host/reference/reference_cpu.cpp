// reference_cpu.cpp: the same walk and booking as simulate.comp (walk.glsl, tally.glsl), on the CPU (the twin).
// Each thread fills a private fixed-point histogram; integer sums make the merge order irrelevant.
#include "angle_policy.h"
#include "reference.h"
#include "cpu_twin.h"
#include "stack_gpu.h"

#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace gonio {

SimResult simulate_cpu(const Stack& stack, const SimOptions& opt, unsigned threads) {
    validate_options(opt);
    validate_stack(stack);
    if (opt.fault_for_tests != 0 || opt.invalid_path_for_tests != 0xffffffffu)
        throw std::invalid_argument("simulate_cpu: the tests' faults and invalid path are the GPU walk's alone");
    if (threads == 0) threads = 1;
    const WalkGrid grid = walk_grid(opt.dtheta_deg, opt.dphi_deg, opt.orders, stack.transmissive());
    const size_t n_values = grid.values();
    const WalkStack walk = walk_stack_for(stack, opt);
    SimResult res =
        start_result(stack, opt, "CPU twin", std::to_string(threads) + " threads", grid, walk_ran(walk, opt, false));
    const float inv_dtheta = float(180.0 / (M_PI * opt.dtheta_deg));
    const float inv_dphi = float(180.0 / (M_PI * opt.dphi_deg));

    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        AngleResult ar;
        ar.theta_i_deg = opt.theta_i_deg[a];
        ar.phi_i_deg = opt.phi_i_deg;
        ar.paths = opt.paths;
        const vec3 travel = incident_travel_of(ar.theta_i_deg, ar.phi_i_deg);
        auto t0 = std::chrono::steady_clock::now();
        std::vector<std::vector<uint64_t>> hists(threads, std::vector<uint64_t>(n_values, 0));
        std::vector<std::array<int64_t, kEnergyEntries>> energies(threads, std::array<int64_t, kEnergyEntries>{});
        std::vector<std::thread> pool;
        for (unsigned t = 0; t < threads; ++t) {
            pool.emplace_back([&, t] {
                CpuTwin twin(walk.gpu, walk.spec, opt.orders, hists[t].data(), energies[t].data());
                CpuTwin::Tally tally;
                twin.tally_begin(tally, res.n_theta, res.n_phi, inv_dtheta, inv_dphi);
                const uvec2 mix = rng_seed_mix(opt.seed, uint32_t(a));
                uint64_t begin = opt.paths * t / threads, end = opt.paths * (t + 1) / threads;
                for (uint64_t i = begin; i < end; ++i) {
                    Rng rng = rng_init_mixed(uint32_t(i), uint32_t(i >> 32), mix);
                    twin.trace_and_book(travel, rng, opt.max_events, tally, 0u, false);
                }
                twin.tally_end(tally, 0u);
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

double mean_events_per_path(const Stack& stack, const SimOptions& opt, uint64_t paths) {
    validate_options(opt);
    const WalkStack walk = walk_stack_for(stack, opt);
    CpuWalker walker(walk.gpu, walk.spec);
    const vec3 travel = incident_travel_of(opt.theta_i_deg.at(0), opt.phi_i_deg);
    const uvec2 mix = rng_seed_mix(opt.seed, 0u);
    uint64_t events = 0;
    for (uint64_t i = 0; i < paths; ++i) {
        Rng rng = rng_init_mixed(uint32_t(i), uint32_t(i >> 32), mix);
        events += walker.trace_path(travel, rng, opt.max_events).events;
    }
    return paths > 0 ? double(events) / double(paths) : 0.0;
}

}   // namespace gonio
