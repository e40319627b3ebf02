// reference_session.cpp: shaders/simulate.comp and fold.comp, kept alive, in slices that do not block the host.
#include "reference_session.h"
#include "compute_kernel.h"
#include "fold_kernel.h"
#include "histogram.h"
#include "stack_gpu.h"
#include "vk_context.h"
#include "walk_dispatch.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>

#include "simulate_spv.h"

namespace gonio {

namespace {

struct Push {   // shaders/simulate.comp's push constants (as in reference_gpu.cpp)
    uint32_t path_base_lo, path_base_hi, path_count, seed_mix0, seed_mix1, max_events, n_theta, n_phi;
    float sin_ti, cos_ti, inv_dtheta, inv_dphi;
};
static_assert(sizeof(Push) == 48);


}  // namespace

struct ReferenceSession::Impl {
    VkContext& ctx;
    SessionOptions opt;
    uint32_t n_theta, n_phi;
    size_t n_values, n_staging;   // capacity: both sides
    size_t n_active = 0;          // values of the current stack's sides (an opaque stack has no transmission bins)
    Buffer ubo, staging, totals, energy, host;
    std::unique_ptr<ComputeKernel> fold;
    // simulate.comp pipelines by specialisation (one entry for the general walk)
    std::map<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, bool>, std::unique_ptr<ComputeKernel>> sims;
    ComputeKernel* sim = nullptr;
    vk::raii::QueryPool queries = nullptr;
    vk::raii::CommandBuffer cb = nullptr;
    vk::raii::Fence fence = nullptr;
    Push pc{};
    bool started = false, in_flight = false;
    uint64_t done = 0, flight_paths = 0, last_paths = 0;
    uint64_t staged = 0;          // paths in the staging histogram, not yet folded into the totals
    uint32_t weight_shift = 0;    // the staging holds weights x 2^-shift (the Lambertian series; fold.comp)
    uint64_t readable = 0;        // paths in the readback copy
    bool flight_readback = false;
    double last_device = 0, device_total = 0;
    SimResult res;

    Impl(VkContext& c, const SessionOptions& o) : ctx(c), opt(o) {
        SimOptions so;
        so.dtheta_deg = o.dtheta_deg;
        so.dphi_deg = o.dphi_deg;
        so.max_events = o.max_events;
        so.paths_per_invocation = o.paths_per_invocation;
        validate_options(so);
        n_theta = uint32_t(std::lround(90.0 / o.dtheta_deg));
        n_phi = uint32_t(std::lround(360.0 / o.dphi_deg));
        n_values = size_t(2) * n_theta * n_phi * 6;
        n_staging = n_values / 2;
        auto& dev = ctx.device();
        ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
        staging = ctx.make_device_buffer(n_staging * 8, vk::BufferUsageFlagBits::eStorageBuffer);
        totals = ctx.make_device_buffer(n_values * 8, vk::BufferUsageFlagBits::eStorageBuffer);
        energy = ctx.make_device_buffer(kEnergyEntries * 8, vk::BufferUsageFlagBits::eStorageBuffer);
        host = ctx.make_buffer(n_values * 8 + kEnergyEntries * 8, vk::BufferUsageFlagBits::eTransferDst, false);
        fold = make_fold_kernel(dev, staging, totals);
        fold_workgroups(n_staging);   // throws if the bins do not fit one fold dispatch
        queries = vk::raii::QueryPool(dev, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
        cb = std::move(vk::raii::CommandBuffers(dev, {.commandPool = *ctx.pool(), .level = vk::CommandBufferLevel::ePrimary,
                                                      .commandBufferCount = 1}).front());
        fence = vk::raii::Fence(dev, vk::FenceCreateInfo{});
        res.options = so;
        res.options.theta_i_deg = {0.0};
        res.options.seed = o.seed;
        res.options.specialised = o.specialised;
        res.device = ctx.device_info().name;
        res.driver = ctx.driver_string();
        res.n_theta = n_theta;
        res.n_phi = n_phi;
        res.n_classes = 1;
        res.angles.resize(1);
    }

    ComputeKernel* pipeline_for(const Stack& s) {
        WalkSpec ws = walk_spec(s, opt.specialised, true, false, opt.max_events);
        // the general walk reads everything from the uniform block: one pipeline for every stack
        auto key = opt.specialised ? std::make_tuple(ws.layer_count, ws.base_kind, ws.rough_mask, ws.absorb_mask, ws.series)
                                   : std::make_tuple(0u, 0u, 0u, 0u, false);
        auto& k = sims[key];
        if (!k) {
            auto& dev = ctx.device();
            k = std::make_unique<ComputeKernel>(dev, simulate_spv, sizeof(simulate_spv),
                std::vector<vk::DescriptorType>{vk::DescriptorType::eUniformBuffer, vk::DescriptorType::eStorageBuffer,
                                                vk::DescriptorType::eStorageBuffer}, uint32_t(sizeof(Push)));
            k->bind(dev, {&ubo, &staging, &energy});
            if (!opt.specialised) ws = WalkSpec{.specialised = false, .layer_count = 2};
            build_walk_kernel(*k, dev, ws, false, opt.paths_per_invocation);
        }
        return k.get();
    }

    void collect() {
        if (!in_flight) return;
        while (ctx.device().waitForFences(*fence, VK_TRUE, 1000000000ull) == vk::Result::eTimeout) {}
        finish();
    }
    void finish() {
        auto [qr, ts] = queries.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                     vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
        last_device = double(ts[1] - ts[0]) * ctx.timestamp_period_ns() * 1e-9;
        device_total += last_device;
        done += flight_paths;
        if (flight_readback) readable = done;
        last_paths = flight_paths;
        flight_paths = 0;
        in_flight = false;
    }
};

ReferenceSession::ReferenceSession(VkContext& ctx, const SessionOptions& opt) : impl_(std::make_unique<Impl>(ctx, opt)) {}

ReferenceSession::~ReferenceSession() {
    if (impl_) impl_->collect();
}

void ReferenceSession::restart(const Stack& stack, double theta_i_deg) {
    Impl& m = *impl_;
    validate_stack(stack);
    if (!(theta_i_deg >= 0.0 && theta_i_deg < 90.0))
        throw std::invalid_argument("incident angle must be in [0, 90) degrees, got " + std::to_string(theta_i_deg));
    m.collect();
    m.sim = m.pipeline_for(stack);
    const WalkSpec ws = walk_spec(stack, m.opt.specialised, true, false, m.opt.max_events);
    StackGpu sg = pack_walk_stack(stack, ws);
    m.weight_shift = uint32_t(walk_weight_shift(stack, ws));
    m.res.n_sides = stack.transmissive() ? 2 : 1;
    m.n_active = size_t(m.res.n_sides) * m.n_theta * m.n_phi * 6;
    std::memcpy(m.ubo.mapped, &sg, sizeof(sg));
    m.ctx.run_now([&](vk::CommandBuffer c) {
        vk::MemoryBarrier before{.srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferRead,
                                 .dstAccessMask = vk::AccessFlagBits::eTransferWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer,
                          vk::PipelineStageFlagBits::eTransfer, {}, before, nullptr, nullptr);
        c.fillBuffer(*m.staging.buffer, 0, VK_WHOLE_SIZE, 0);
        c.fillBuffer(*m.totals.buffer, 0, VK_WHOLE_SIZE, 0);
        c.fillBuffer(*m.energy.buffer, 0, VK_WHOLE_SIZE, 0);
        vk::MemoryBarrier mb{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                             .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, mb, nullptr, nullptr);
    });
    std::memset(m.host.mapped, 0, m.n_values * 8 + kEnergyEntries * 8);
    const double ti = theta_i_deg * M_PI / 180.0;
    m.pc = Push{};
    const uvec2 mix = rng_seed_mix(m.opt.seed, 0u);   // stream 0: one incident angle, as rng_init
    m.pc.seed_mix0 = mix.x;
    m.pc.seed_mix1 = mix.y;
    m.pc.max_events = m.opt.max_events;
    m.pc.n_theta = m.n_theta;
    m.pc.n_phi = m.n_phi;
    m.pc.sin_ti = float(std::sin(ti));
    m.pc.cos_ti = float(std::cos(ti));
    m.pc.inv_dtheta = float(180.0 / (M_PI * m.opt.dtheta_deg));
    m.pc.inv_dphi = float(180.0 / (M_PI * m.opt.dphi_deg));
    m.done = 0;
    m.staged = 0;
    m.readable = 0;
    m.device_total = 0;
    m.last_device = 0;
    m.last_paths = 0;
    m.res.stack = stack;
    m.res.options.theta_i_deg = {theta_i_deg};
    m.res.angles.assign(1, AngleResult{});
    m.res.angles[0].theta_i_deg = theta_i_deg;
    m.started = true;
}

bool ReferenceSession::submit(uint64_t paths, bool readback) {
    Impl& m = *impl_;
    if (!m.started) throw std::logic_error("ReferenceSession::submit before restart");
    if (m.in_flight) return false;
    const WalkDispatch wd(m.opt.paths_per_invocation);
    const uint64_t per_group = wd.per_group, max_batch = wd.max_paths;
    const uint64_t n = std::clamp<uint64_t>((paths + per_group - 1) / per_group * per_group, per_group, max_batch);
    m.pc.path_base_lo = uint32_t(m.done);
    m.pc.path_base_hi = uint32_t(m.done >> 32);
    m.pc.path_count = uint32_t(n);
    const uint32_t groups = uint32_t(n / per_group);
    auto& cb = m.cb;
    cb.reset();
    cb.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    cb.resetQueryPool(*m.queries, 0, 2);
    cb.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *m.queries, 0);
    // the previous slice's readback copy reads the totals this slice's fold writes
    // the previous slices' atomics, fold and readback copy touch what this slice's dispatches touch
    vk::MemoryBarrier start{.srcAccessMask = vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eTransferWrite |
                                             vk::AccessFlagBits::eShaderWrite,
                            .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
    cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer | vk::PipelineStageFlagBits::eComputeShader,
                       vk::PipelineStageFlagBits::eComputeShader, {}, start, nullptr, nullptr);
    const vk::MemoryBarrier between{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                    .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
    auto fold = [&] {
        record_fold(*cb, *m.fold, m.n_active / 2, m.weight_shift);
        m.staged = 0;
    };
    // the packed staging sums must not carry (bins.glsl): at most MAX_PATHS_PER_DISPATCH paths between folds
    if (m.staged + n > MAX_PATHS_PER_DISPATCH) {
        fold();
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, between, nullptr, nullptr);
    }
    cb.bindPipeline(vk::PipelineBindPoint::eCompute, *m.sim->pipeline);
    cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *m.sim->layout, 0, {*m.sim->set}, nullptr);
    cb.pushConstants<Push>(*m.sim->layout, vk::ShaderStageFlagBits::eCompute, 0, m.pc);
    cb.dispatch(groups, 1, 1);
    m.staged += n;
    if (readback) {
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eComputeShader, {}, between, nullptr, nullptr);
        fold();
    }
    if (readback) {
        vk::MemoryBarrier to_copy{.srcAccessMask = vk::AccessFlagBits::eShaderWrite, .dstAccessMask = vk::AccessFlagBits::eTransferRead};
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, to_copy, nullptr, nullptr);
        cb.copyBuffer(*m.totals.buffer, *m.host.buffer, vk::BufferCopy{0, 0, m.n_active * 8});
        cb.copyBuffer(*m.energy.buffer, *m.host.buffer, vk::BufferCopy{0, m.n_values * 8, kEnergyEntries * 8});
        vk::MemoryBarrier to_host{.srcAccessMask = vk::AccessFlagBits::eTransferWrite, .dstAccessMask = vk::AccessFlagBits::eHostRead};
        cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, to_host, nullptr, nullptr);
    }
    cb.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *m.queries, 1);
    cb.end();
    m.ctx.device().resetFences(*m.fence);
    vk::CommandBuffer h = *cb;
    m.ctx.queue().submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &h}, *m.fence);
    m.in_flight = true;
    m.flight_paths = n;
    m.flight_readback = readback;
    return true;
}

bool ReferenceSession::poll() {
    Impl& m = *impl_;
    if (!m.in_flight) return true;
    if (m.fence.getStatus() != vk::Result::eSuccess) return false;
    m.finish();
    return true;
}

void ReferenceSession::wait() { impl_->collect(); }

uint64_t ReferenceSession::paths() const { return impl_->done; }
uint64_t ReferenceSession::readable_paths() const { return impl_->readable; }
double ReferenceSession::last_slice_device_seconds() const { return impl_->last_device; }
uint64_t ReferenceSession::last_slice_paths() const { return impl_->last_paths; }
double ReferenceSession::device_seconds() const { return impl_->device_total; }
bool ReferenceSession::busy() const { return impl_->in_flight; }

const SimResult& ReferenceSession::result() {
    Impl& m = *impl_;
    if (m.in_flight) throw std::logic_error("ReferenceSession::result while a slice is in flight");
    AngleResult& a = m.res.angles[0];
    const uint64_t* t = static_cast<const uint64_t*>(m.host.mapped);
    a.paths = m.readable;
    a.raw.assign(t, t + m.n_active);
    std::memcpy(a.energy, t + m.n_values, sizeof(a.energy));
    a.device_seconds = m.device_total;
    m.res.options.paths = std::max<uint64_t>(m.readable, 1);
    return m.res;
}

double median_relative_se(const SimResult& r, const AngleResult& a, int side) {
    if (a.paths < 2) return 0.0;
    Slice s = make_slice(r, a, Side(side));
    std::vector<double> rel;
    for (int c = 0; c < 3; ++c) {
        double peak = 0;
        for (auto& v : s.f) peak = std::max(peak, v[c]);
        if (peak <= 0) continue;
        for (size_t b = 0; b < s.f.size(); ++b)
            if (s.f[b][c] > 0.01 * peak) rel.push_back(s.se[b][c] / s.f[b][c]);
    }
    if (rel.empty()) return 0.0;
    std::nth_element(rel.begin(), rel.begin() + rel.size() / 2, rel.end());
    return rel[rel.size() / 2];
}

}  // namespace gonio
