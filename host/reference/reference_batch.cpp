// reference_batch.cpp: runs shaders/simulate_batch.comp: many stacks per dispatch (see reference.h).
#include "reference.h"
#include "compute_kernel.h"
#include "fold_kernel.h"
#include "histogram.h"
#include "stack_gpu.h"
#include "vk_context.h"
#include "walk_dispatch.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "simulate_batch_spv.h"

namespace gonio {

namespace {

struct BatchPush {
    uint32_t path_base_lo, path_base_hi, path_count, unused_seed, stream, max_events, n_theta, n_phi;
    float sin_ti, cos_ti, inv_dtheta, inv_dphi;
    uint32_t staging_stride;
};

struct BatchStack {           // std430 layout of BatchStack in simulate_batch.comp
    LayerGpu layers[MAX_LAYERS];
    vec4 info;
    SeriesGpu series;
    uint32_t extra[4];
};
static_assert(sizeof(BatchStack) == 64 * MAX_LAYERS + 80);


bool same_spec(const WalkSpec& a, const WalkSpec& b) {
    return a.specialised == b.specialised && a.layer_count == b.layer_count && a.base_kind == b.base_kind &&
           a.rough_mask == b.rough_mask && a.absorb_mask == b.absorb_mask && a.series == b.series;
}

}  // namespace

std::vector<SimResult> simulate_gpu_batch(VkContext& ctx, const std::vector<Stack>& stacks, const std::vector<uint32_t>& seeds,
                                          const SimOptions& opt) {
    validate_options(opt);
    if (stacks.empty()) return {};
    if (seeds.size() != stacks.size()) throw std::invalid_argument("simulate_gpu_batch: one seed per stack");
    if (opt.max_seconds > 0) throw std::invalid_argument("simulate_gpu_batch: no --max-seconds (a batch's stacks share their time)");
    if (stacks.size() > 65535) throw std::invalid_argument("simulate_gpu_batch: at most 65535 stacks per batch");
    const WalkSpec ws = walk_spec(stacks[0], opt.specialised, opt.series, opt.orders, opt.max_events);
    int weight_shift = 0;     // one staging scale for the whole batch: the largest any stack needs
    for (const Stack& s : stacks) {
        validate_stack(s);
        WalkSpec w = walk_spec(s, opt.specialised, opt.series, opt.orders, opt.max_events);
        weight_shift = std::max(weight_shift, walk_weight_shift(s, w));
        if (w.layer_count != ws.layer_count || w.base_kind != ws.base_kind)
            throw std::invalid_argument("simulate_gpu_batch: the stacks of a batch must have the same layers and base kind");
        if (opt.specialised && !same_spec(w, ws))
            throw std::invalid_argument("simulate_gpu_batch: stacks with different rough or absorbing layers, or where the "
                                        "Lambertian series applies to some but not all, need the general walk");
    }
    const size_t C = stacks.size();
    std::vector<SimResult> res(C);
    const uint32_t n_theta = uint32_t(std::lround(90.0 / opt.dtheta_deg)), n_phi = uint32_t(std::lround(360.0 / opt.dphi_deg));
    const uint32_t n_classes = opt.orders ? 3 : 1;
    const uint32_t n_sides = stacks[0].transmissive() ? 2 : 1;   // the same base kind for every stack (checked above)
    const size_t n_values = size_t(n_classes) * n_sides * n_theta * n_phi * 6, n_staging = n_values / 2;
    check_histograms_fit(ctx, uint64_t(C) * n_values * 8, std::to_string(C) + " configurations per batch of this grid");
    for (size_t i = 0; i < C; ++i) {
        res[i].stack = stacks[i];
        res[i].options = opt;
        res[i].options.seed = seeds[i];
        res[i].device = ctx.device_info().name;
        res[i].driver = ctx.driver_string();
        res[i].n_theta = n_theta;
        res[i].n_phi = n_phi;
        res[i].n_classes = n_classes;
        res[i].n_sides = n_sides;
    }
    auto& dev = ctx.device();
    Buffer sbuf = ctx.make_buffer(C * sizeof(BatchStack), vk::BufferUsageFlagBits::eStorageBuffer, true);
    {
        std::vector<BatchStack> bs(C);
        for (size_t i = 0; i < C; ++i) {
            StackGpu g = pack_walk_stack(stacks[i], ws, weight_shift);
            std::memcpy(bs[i].layers, g.layers, sizeof g.layers);
            bs[i].info = g.info;
            bs[i].series = g.series;
            bs[i].extra[0] = seeds[i];
            bs[i].extra[1] = 1;   // active
            bs[i].extra[2] = bs[i].extra[3] = 0;
        }
        std::memcpy(sbuf.mapped, bs.data(), C * sizeof(BatchStack));
    }
    Buffer staging = ctx.make_device_buffer(C * n_staging * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer totals = ctx.make_device_buffer(C * n_values * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer energy = ctx.make_device_buffer(C * kEnergyEntries * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    Buffer host = ctx.make_buffer(C * (n_values + kEnergyEntries) * 8, vk::BufferUsageFlagBits::eTransferDst, false);
    const uint64_t* host_totals = static_cast<const uint64_t*>(host.mapped);
    const int64_t* host_energy = reinterpret_cast<const int64_t*>(host_totals + C * n_values);

    ComputeKernel sim(dev, simulate_batch_spv, sizeof(simulate_batch_spv), {vk::DescriptorType::eStorageBuffer,
                      vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer}, sizeof(BatchPush));
    sim.bind(dev, {&sbuf, &staging, &energy});
    build_walk_kernel(sim, dev, ws, opt.orders, opt.paths_per_invocation);
    std::unique_ptr<ComputeKernel> fold_kernel = make_fold_kernel(dev, staging, totals);
    ComputeKernel& fold = *fold_kernel;
    const uint64_t fold_elems = uint64_t(C) * n_staging;
    fold_workgroups(fold_elems);   // throws if the bins do not fit one fold dispatch

    vk::raii::QueryPool queries(dev, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    const WalkDispatch wd(opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    // paths per dispatch, per stack: about 2^20 path-stacks per submission (results do not depend on it)
    uint64_t batch = std::max<uint64_t>(per_group, std::min<uint64_t>(max_batch, ((1ull << 20) / C / per_group + 1) * per_group));
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        ctx.run_now([&](vk::CommandBuffer c) {
            c.fillBuffer(*staging.buffer, 0, VK_WHOLE_SIZE, 0);
            c.fillBuffer(*totals.buffer, 0, VK_WHOLE_SIZE, 0);
            c.fillBuffer(*energy.buffer, 0, VK_WHOLE_SIZE, 0);
            vk::MemoryBarrier mb{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                 .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
            c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, mb, nullptr, nullptr);
        });
        double ti = opt.theta_i_deg[a] * M_PI / 180.0;
        BatchPush pc{};
        pc.stream = uint32_t(a);
        pc.max_events = opt.max_events;
        pc.n_theta = n_theta;
        pc.n_phi = n_phi;
        pc.sin_ti = float(std::sin(ti));
        pc.cos_ti = float(std::cos(ti));
        pc.inv_dtheta = float(180.0 / (M_PI * opt.dtheta_deg));
        pc.inv_dphi = float(180.0 / (M_PI * opt.dphi_deg));
        pc.staging_stride = uint32_t(n_staging);
        double device_seconds = 0;
        auto t0 = std::chrono::steady_clock::now();
        BatchStack* live = static_cast<BatchStack*>(sbuf.mapped);
        for (size_t i = 0; i < C; ++i) live[i].extra[1] = 1;
        // --rse: as simulate_gpu, paths grow in rounds (checkpoints at 2^20 x 2^k, capped by opt.paths) and a
        // stack stops at the first checkpoint where its worst relative standard error meets the target, so each
        // stack gets exactly the paths (and bits) of its own simulate_gpu run. Stopped stacks stay in the
        // dispatch but their workgroups return at once.
        auto next_checkpoint = [&](uint64_t from) { return opt.rse_target > 0 ? rse_round_end(from, opt.paths) : opt.paths; };
        std::vector<std::string> stopped_by(C, "paths");
        size_t active = C;
        uint64_t done = 0, checkpoint = next_checkpoint(0);
        auto read_back = [&]() {
            ctx.run_now([&](vk::CommandBuffer c) {
                vk::MemoryBarrier before{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eTransferRead};
                c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, before, nullptr, nullptr);
                c.copyBuffer(*totals.buffer, *host.buffer, vk::BufferCopy{0, 0, C * n_values * 8});
                c.copyBuffer(*energy.buffer, *host.buffer, vk::BufferCopy{0, C * n_values * 8, C * kEnergyEntries * 8});
                vk::MemoryBarrier after{.srcAccessMask = vk::AccessFlagBits::eTransferWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
                c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, after, nullptr, nullptr);
            });
        };
        auto angle_of = [&](size_t i, uint64_t paths) {
            AngleResult ar;
            ar.theta_i_deg = opt.theta_i_deg[a];
            ar.paths = paths;
            ar.raw.assign(host_totals + i * n_values, host_totals + (i + 1) * n_values);
            std::memcpy(ar.energy, host_energy + i * kEnergyEntries, sizeof(ar.energy));
            return ar;
        };
        std::vector<AngleResult> finished(C);
        while (active > 0 && done < opt.paths) {
            uint64_t n = std::min(batch, checkpoint - done);
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            uint32_t groups = wd.groups(n);
            ctx.run_now([&](vk::CommandBuffer c) {
                c.resetQueryPool(*queries, 0, 2);
                c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
                c.bindPipeline(vk::PipelineBindPoint::eCompute, *sim.pipeline);
                c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *sim.layout, 0, {*sim.set}, nullptr);
                c.pushConstants<BatchPush>(*sim.layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
                c.dispatch(groups, uint32_t(C), 1);
                vk::MemoryBarrier between{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                          .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
                c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, between, nullptr, nullptr);
                record_fold(c, fold, fold_elems, uint32_t(weight_shift));
                c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries, 1);
                c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, between, nullptr, nullptr);
            });
            auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                         vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
            device_seconds += double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
            done += n;
            if (opt.rse_target > 0 && done == checkpoint && done < opt.paths) {
                read_back();
                for (size_t i = 0; i < C; ++i) {
                    if (!live[i].extra[1]) continue;
                    AngleResult cur = angle_of(i, done);
                    double rse = relative_se_quantile(res[i], cur, opt.rse_quantile);
                    if (rse <= opt.rse_target && rse > 0) {   // as simulate_gpu: stop here
                        live[i].extra[1] = 0;
                        active--;
                        stopped_by[i] = "rse";
                        finished[i] = std::move(cur);
                    }
                }
                checkpoint = next_checkpoint(done);
            }
        }
        read_back();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (size_t i = 0; i < C; ++i) {
            AngleResult ar = live[i].extra[1] ? angle_of(i, done) : std::move(finished[i]);
            ar.seconds = seconds / double(C);            // shared: each stack's share of the batch
            ar.device_seconds = device_seconds / double(C);
            summarise_relative_se(res[i], ar);
            if (live[i].extra[1]) {
                // the last checkpoint is the cap: simulate_gpu reports "rse" there if the target is met
                const double rse = relative_se_quantile(res[i], ar, opt.rse_quantile);
                ar.stopped_by = opt.rse_target > 0 && rse <= opt.rse_target && rse > 0 ? "rse" : "paths";
            } else {
                ar.stopped_by = stopped_by[i];
            }
            res[i].angles.push_back(std::move(ar));
        }
    }
    return res;
}

}  // namespace gonio
