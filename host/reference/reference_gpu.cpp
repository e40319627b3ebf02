// reference_gpu.cpp: runs shaders/simulate.comp through Vulkan.
#include "reference.h"
#include "state.h"
#include "compute_kernel.h"
#include "fold_kernel.h"
#include "histogram.h"
#include "progress.h"
#include "stack_gpu.h"
#include "text_format.h"
#include "vk_context.h"
#include "walk_dispatch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "simulate_spv.h"

namespace gonio {

namespace {

struct Push {
    uint32_t path_base_lo, path_base_hi, path_count, seed_mix0, seed_mix1, max_events, n_theta, n_phi;
    float sin_ti, cos_ti, inv_dtheta, inv_dphi;
};
static_assert(sizeof(Push) == 48);


}  // namespace

void validate_options(const SimOptions& o) {
    auto divides = [](double w, double range) {
        double n = range / w;
        return w > 0 && std::fabs(n - std::round(n)) < 1e-9 && n >= 1;
    };
    if (o.theta_i_deg.empty()) throw std::invalid_argument("--theta-i: at least one incident angle is needed");
    for (double t : o.theta_i_deg)
        if (!(t >= 0.0 && t < 90.0))
            throw std::invalid_argument("--theta-i: incident angles must be in [0, 90) degrees, got " + std::to_string(t));
    if (o.paths == 0) throw std::invalid_argument("--paths must be at least 1");
    if (o.paths > kMaxPathsPerAngle)
        throw std::invalid_argument("--paths: at most " + format_g9(double(kMaxPathsPerAngle)) +
                                    " paths per incident angle (the 64-bit energy book holds no more), got " + format_g9(double(o.paths)));
    if (!divides(o.dtheta_deg, 90.0)) throw std::invalid_argument("--dtheta must divide 90 degrees into a whole number of bins");
    if (!divides(o.dphi_deg, 180.0)) throw std::invalid_argument("--dphi must divide 180 degrees into a whole number of bins");
    if (o.max_events < 1) throw std::invalid_argument("--max-events must be at least 1");
    // lavapipe silently ends every loop of an invocation after 65535 iterations in total (docs/PHYSICS.md).
    if (uint64_t(o.paths_per_invocation) * (uint64_t(o.max_events) + 2) + o.paths_per_invocation + 8 >= 65535)
        throw std::invalid_argument("--max-events " + std::to_string(o.max_events) + " is too large: paths per invocation (" +
                                    std::to_string(o.paths_per_invocation) + ") x (max events + 2) must stay below 65535");
}

void check_histograms_fit(VkContext& ctx, uint64_t bytes, const std::string& what) {
    const vk::PhysicalDeviceProperties p = ctx.physical().getProperties();
    const vk::PhysicalDeviceMemoryProperties m = ctx.physical().getMemoryProperties();
    uint64_t heap = 0;
    for (uint32_t i = 0; i < m.memoryHeapCount; ++i)
        if (m.memoryHeaps[i].flags & vk::MemoryHeapFlagBits::eDeviceLocal) heap = std::max<uint64_t>(heap, m.memoryHeaps[i].size);
    const uint64_t range = p.limits.maxStorageBufferRange;
    auto mib = [](double b) { return format_g9(std::round(b / 1048576.0 * 10) / 10) + " MiB"; };
    if (bytes > range)
        throw std::invalid_argument(what + " needs a histogram buffer of " + mib(double(bytes)) + "; the device allows " +
                                    mib(double(range)) + " per buffer: use wider --dtheta / --dphi");
    if (heap > 0 && 3 * bytes > heap / 2)   // totals, staging and the host copy, within half the device's memory
        throw std::invalid_argument(what + " needs " + mib(3.0 * double(bytes)) + " of histograms; the device has " +
                                    mib(double(heap)) + ": use wider --dtheta / --dphi");
}

SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt, const SimResult* resume) {
    validate_options(opt);
    validate_stack(stack);
    if (resume) check_resumable(*resume, stack, opt);
    SimResult res;
    res.stack = stack;
    res.options = opt;
    res.device = ctx.device_info().name;
    res.driver = ctx.driver_string();
    res.n_theta = uint32_t(std::lround(90.0 / opt.dtheta_deg));
    res.n_phi = uint32_t(std::lround(360.0 / opt.dphi_deg));
    res.n_classes = opt.orders ? 3 : 1;
    res.n_sides = stack.transmissive() ? 2 : 1;
    const size_t n_values = size_t(res.n_classes) * res.n_sides * res.n_theta * res.n_phi * 6;
    check_histograms_fit(ctx, uint64_t(n_values) * 8,
                         "a grid of " + std::to_string(res.n_theta) + " x " + std::to_string(res.n_phi) + " bins");

    auto& dev = ctx.device();
    WalkSpec ws = walk_spec(stack, opt.specialised, opt.series, opt.orders, opt.max_events);
    StackGpu sg = pack_walk_stack(stack, ws);
    const uint32_t weight_shift = uint32_t(walk_weight_shift(stack, ws));

    const size_t n_staging = n_values / 2;   // one packed value per bin and channel
    Buffer ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
    std::memcpy(ubo.mapped, &sg, sizeof(sg));
    // The histograms live in device-local memory; `host` is the mapped buffer they are uploaded from and
    // read back into (totals first, then the 9 energy entries).
    Buffer staging = ctx.make_device_buffer(n_staging * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer totals = ctx.make_device_buffer(n_values * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer energy = ctx.make_device_buffer(kEnergyEntries * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer host = ctx.make_buffer(n_values * 8 + kEnergyEntries * 8, vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst, false);
    uint64_t* host_totals = static_cast<uint64_t*>(host.mapped);
    int64_t* host_energy = reinterpret_cast<int64_t*>(host_totals + n_values);
    const vk::DeviceSize energy_offset = n_values * 8;
    auto transfer = [&](bool upload) {        // host <-> (totals, energy), waiting for it
        ctx.run_now([&](vk::CommandBuffer c) {
            vk::MemoryBarrier before{.srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eHostWrite,
                                     .dstAccessMask = vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eTransferWrite};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eHost,
                              vk::PipelineStageFlagBits::eTransfer, {}, before, nullptr, nullptr);
            if (upload) {
                c.copyBuffer(*host.buffer, *totals.buffer, vk::BufferCopy{0, 0, n_values * 8});
                c.copyBuffer(*host.buffer, *energy.buffer, vk::BufferCopy{energy_offset, 0, kEnergyEntries * 8});
            } else {
                c.copyBuffer(*totals.buffer, *host.buffer, vk::BufferCopy{0, 0, n_values * 8});
                c.copyBuffer(*energy.buffer, *host.buffer, vk::BufferCopy{0, energy_offset, kEnergyEntries * 8});
            }
            vk::MemoryBarrier after{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                    .dstAccessMask = vk::AccessFlagBits::eHostRead | vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                              vk::PipelineStageFlagBits::eHost | vk::PipelineStageFlagBits::eComputeShader, {}, after, nullptr, nullptr);
        });
    };
    ctx.run_now([&](vk::CommandBuffer c) {
        c.fillBuffer(*staging.buffer, 0, VK_WHOLE_SIZE, 0);
        vk::MemoryBarrier mb{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                             .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, mb, nullptr, nullptr);
    });

    ComputeKernel sim(dev, simulate_spv, sizeof(simulate_spv), {vk::DescriptorType::eUniformBuffer,
                      vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer}, sizeof(Push));
    sim.bind(dev, {&ubo, &staging, &energy});
    // a specialised walk of one or two layers gets the stack compiled in (stack_constants.glsl)
    build_walk_kernel(sim, dev, ws, opt.orders, opt.paths_per_invocation,
                      opt.baked_stack && walk_has_constant_stack(ws) ? &sg : nullptr, opt.invalid_path_for_tests);

    std::unique_ptr<ComputeKernel> fold_kernel = make_fold_kernel(dev, staging, totals);
    ComputeKernel& fold = *fold_kernel;
    fold_workgroups(n_staging);   // throws if the bins do not fit one fold dispatch

    vk::raii::QueryPool queries(dev, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    vk::raii::CommandBuffer cb = std::move(vk::raii::CommandBuffers(dev, {.commandPool = *ctx.pool(), .level = vk::CommandBufferLevel::ePrimary, .commandBufferCount = 1}).front());

    const WalkDispatch wd(opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    uint64_t batch = opt.batch_paths ? std::min<uint64_t>(opt.batch_paths, max_batch) : std::min<uint64_t>(1u << 16, max_batch);

    Progress progress(opt.progress, stack.name, opt.paths * opt.theta_i_deg.size());
    auto last_checkpoint = std::chrono::steady_clock::now();
    uint64_t done_all = 0;
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        AngleResult ar;
        ar.theta_i_deg = opt.theta_i_deg[a];
        std::memset(host_totals, 0, n_values * 8);
        std::memset(host_energy, 0, kEnergyEntries * 8);
        uint64_t done = 0;
        if (resume) {                                    // continue the earlier run's sums and path numbering
            const AngleResult& prev = resume->angles[a];
            std::memcpy(host_totals, prev.raw.data(), n_values * 8);
            std::memcpy(host_energy, prev.energy, sizeof(prev.energy));
            done = prev.paths;
            ar.seconds = prev.seconds;
            ar.device_seconds = prev.device_seconds;
        }
        transfer(true);
        // In --rse mode the paths grow in rounds (2^20 x 2^k), checked at the end of each round.
        auto next_checkpoint = [&](uint64_t from) { return opt.rse_target > 0 ? rse_round_end(from, opt.paths) : opt.paths; };
        uint64_t checkpoint = next_checkpoint(done);
        auto snapshot = [&](uint64_t paths) {
            transfer(false);
            AngleResult cur;
            cur.paths = paths;
            cur.raw.assign(host_totals, host_totals + n_values);
            std::memcpy(cur.energy, host_energy, sizeof(cur.energy));
            return cur;
        };
        double shown_rse = 0.0;
        double ti = opt.theta_i_deg[a] * M_PI / 180.0;
        Push pc{};
        const uvec2 mix = rng_seed_mix(opt.seed, uint32_t(a));   // as rng_init (shaders/lib/rng.glsl)
        pc.seed_mix0 = mix.x;
        pc.seed_mix1 = mix.y;
        pc.max_events = opt.max_events;
        pc.n_theta = res.n_theta;
        pc.n_phi = res.n_phi;
        pc.sin_ti = float(std::sin(ti));
        pc.cos_ti = float(std::cos(ti));
        pc.inv_dtheta = float(180.0 / (M_PI * opt.dtheta_deg));
        pc.inv_dphi = float(180.0 / (M_PI * opt.dphi_deg));
        auto t0 = std::chrono::steady_clock::now();
        const double seconds_before = ar.seconds;
        // a resumed angle whose paths end a round (--rse) is checked before tracing more, as one uninterrupted run
        // would have checked it there
        if (opt.rse_target > 0 && done > 0 && done < opt.paths && next_checkpoint(done - 1) == done) {
            shown_rse = relative_se_quantile(res, snapshot(done), opt.rse_quantile);
            if (shown_rse <= opt.rse_target && shown_rse > 0) ar.stopped_by = "rse";
        }
        while (done < opt.paths && ar.stopped_by != "rse") {
            uint64_t n = std::min(batch, checkpoint - done);
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            uint32_t groups = wd.groups(n);
            cb.reset();
            cb.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
            cb.resetQueryPool(*queries, 0, 2);
            cb.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
            cb.bindPipeline(vk::PipelineBindPoint::eCompute, *sim.pipeline);
            cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *sim.layout, 0, {*sim.set}, nullptr);
            cb.pushConstants<Push>(*sim.layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
            cb.dispatch(groups, 1, 1);
            vk::MemoryBarrier between{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                      .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
            cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, between, nullptr, nullptr);
            record_fold(*cb, fold, n_staging, weight_shift);
            cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
            vk::MemoryBarrier mb{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
            cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, mb, nullptr, nullptr);
            cb.end();
            auto b0 = std::chrono::steady_clock::now();
            ctx.submit_and_wait(*cb);
            double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count();
            auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                         vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
            ar.device_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
            done += n;
            done_all += n;
            double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (opt.rse_target > 0 && done == checkpoint) {
                shown_rse = relative_se_quantile(res, snapshot(done), opt.rse_quantile);
                if (shown_rse <= opt.rse_target && shown_rse > 0) { ar.stopped_by = "rse"; break; }
                checkpoint = next_checkpoint(done);
            }
            progress.update(done_all, a, opt.theta_i_deg.size(), opt.theta_i_deg[a],
                            opt.rse_target > 0 ? shown_rse : -1.0, opt.rse_target);
            if (opt.max_seconds > 0 && elapsed >= opt.max_seconds && done < opt.paths) { ar.stopped_by = "max_seconds"; break; }
            if (opt.on_checkpoint && done < opt.paths &&
                std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >= opt.checkpoint_seconds) {
                SimResult partial = res;   // the angles done, this one so far, the others as they were before this run
                AngleResult cur = snapshot(done);
                cur.theta_i_deg = ar.theta_i_deg;
                cur.seconds = seconds_before + elapsed;
                cur.device_seconds = ar.device_seconds;
                cur.stopped_by = "checkpoint";
                partial.angles.push_back(std::move(cur));
                for (size_t b = a + 1; b < opt.theta_i_deg.size(); ++b) {
                    AngleResult later;
                    if (resume) later = resume->angles[b];
                    else later.raw.assign(n_values, 0);
                    later.theta_i_deg = opt.theta_i_deg[b];
                    partial.angles.push_back(std::move(later));
                }
                opt.on_checkpoint(partial);
                last_checkpoint = std::chrono::steady_clock::now();
            }
            // adapt the batch towards ~0.25 s per submission (results do not depend on it)
            if (!opt.batch_paths && dt > 0.0) {
                double target = double(n) * 0.25 / dt;
                uint64_t next = uint64_t(std::clamp(target, double(per_group), double(n) * 4.0));
                batch = std::min<uint64_t>(std::max<uint64_t>(next / per_group, 1) * per_group, max_batch);
            }
        }
        ar.seconds = seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        AngleResult fin = snapshot(done);
        ar.paths = done;
        ar.raw = std::move(fin.raw);
        std::memcpy(ar.energy, fin.energy, sizeof(ar.energy));
        summarise_relative_se(res, ar);
        res.angles.push_back(std::move(ar));
    }
    progress.finish();
    return res;
}

}  // namespace gonio
