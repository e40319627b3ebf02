// walk_runner.cpp: see walk_runner.h.
#include "walk_runner.h"
#include "rng.glsl"   // rng_seed_mix
#include "fold_kernel.h"
#include "incidence.h"
#include "text_format.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace gonio {

WalkPush walk_push(const WalkGrid& g, double dtheta_deg, double dphi_deg, uint32_t max_events, double theta_i_deg,
                   double phi_i_deg, uint32_t seed, uint32_t stream) {
    WalkPush pc{};
    const IncidentTrig trig = incident_trig(theta_i_deg, phi_i_deg);
    const uvec2 mix = rng_seed_mix(seed, stream);   // as rng_init (shaders/lib/rng.glsl)
    pc.seed_mix0 = mix.x;
    pc.seed_mix1 = mix.y;
    pc.stream = stream;
    pc.max_events = max_events;
    pc.n_theta = g.n_theta;
    pc.n_phi = g.n_phi;
    pc.sin_ti = trig.sin_ti;
    pc.cos_ti = trig.cos_ti;
    pc.sin_pi = trig.sin_pi;
    pc.cos_pi = trig.cos_pi;
    pc.inv_dtheta = float(180.0 / (M_PI * dtheta_deg));
    pc.inv_dphi = float(180.0 / (M_PI * dphi_deg));
    return pc;
}

void check_histograms_fit(VkContext& ctx, uint64_t bytes, const std::string& what) {
    const vk::PhysicalDeviceProperties p = ctx.physical().getProperties();
    const vk::PhysicalDeviceMemoryProperties m = ctx.physical().getMemoryProperties();
    uint64_t heap = 0;
    for (uint32_t i = 0; i < m.memoryHeapCount; ++i)
        if (m.memoryHeaps[i].flags & vk::MemoryHeapFlagBits::eDeviceLocal)
            heap = std::max<uint64_t>(heap, m.memoryHeaps[i].size);
    const uint64_t range = p.limits.maxStorageBufferRange;
    auto mib = [](double b) { return format_g9(std::round(b / 1048576.0 * 10) / 10) + " MiB"; };
    if (bytes > range)
        throw std::invalid_argument(what + " needs a histogram buffer of " + mib(double(bytes)) +
                                    "; the device allows " + mib(double(range)) +
                                    " per buffer: use wider --dtheta / --dphi");
    if (heap > 0 && 3 * bytes > heap / 2)   // totals, staging and the host copy, within half the device's memory
        throw std::invalid_argument(what + " needs " + mib(3.0 * double(bytes)) + " of histograms; the device has " +
                                    mib(double(heap)) + ": use wider --dtheta / --dphi");
}

size_t configurations_that_fit(VkContext& ctx, size_t values) {
    const vk::PhysicalDeviceProperties p = ctx.physical().getProperties();
    const vk::PhysicalDeviceMemoryProperties m = ctx.physical().getMemoryProperties();
    uint64_t heap = 0;
    for (uint32_t i = 0; i < m.memoryHeapCount; ++i)
        if (m.memoryHeaps[i].flags & vk::MemoryHeapFlagBits::eDeviceLocal)
            heap = std::max<uint64_t>(heap, m.memoryHeaps[i].size);
    const uint64_t bytes = uint64_t(values) * 8;   // as check_histograms_fit and fold_workgroups count them
    uint64_t n = uint64_t(p.limits.maxStorageBufferRange) / bytes;
    if (heap > 0) n = std::min<uint64_t>(n, heap / 2 / (3 * bytes));
    const uint64_t fold_values = 65535ull * FOLD_LOCAL_SIZE * FOLD_PER_INVOCATION;   // one fold dispatch
    n = std::min<uint64_t>(n, std::min<uint64_t>(fold_values, 0xffffffffull) / (values / 2));
    return size_t(n);
}

WalkRunner::WalkRunner(VkContext& ctx, size_t values, size_t configs, vk::DescriptorType stack_type,
                       vk::DeviceSize stack_bytes, const std::string& what)
    : ctx_(ctx), values_(values), configs_(configs), stack_type_(stack_type) {
    check_histograms_fit(ctx, uint64_t(configs) * values * 8, what);
    const size_t n_staging = configs * values / 2;   // one packed value per bin and channel
    fold_workgroups(n_staging);   // throws if the bins do not fit one fold dispatch
    auto& dev = ctx.device();
    stack_ = ctx.make_buffer(stack_bytes,
                             stack_type == vk::DescriptorType::eUniformBuffer ? vk::BufferUsageFlagBits::eUniformBuffer
                                                                              : vk::BufferUsageFlagBits::eStorageBuffer,
                             true);
    // The histograms live in device-local memory; `host` is the mapped buffer they are uploaded from and read back
    // into (every configuration's totals, then their energy books).
    staging_ = ctx.make_device_buffer(n_staging * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    totals_ = ctx.make_device_buffer(configs * values * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    energy_ = ctx.make_device_buffer(configs * ENERGY_ENTRIES * 8, vk::BufferUsageFlagBits::eStorageBuffer);
    host_ = ctx.make_buffer(configs * (values + ENERGY_ENTRIES) * 8,
                            vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst, false);
    angles_ = ctx.make_buffer(configs * sizeof(WalkAngle), vk::BufferUsageFlagBits::eStorageBuffer, true);
    host_totals_ = static_cast<uint64_t*>(host_.mapped);
    host_energy_ = reinterpret_cast<int64_t*>(host_totals_ + configs * values);
    fold_ = make_fold_kernel(dev, staging_, totals_);
    queries_ =
        vk::raii::QueryPool(dev, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    cb_ = std::move(
        vk::raii::CommandBuffers(
            dev, {.commandPool = *ctx.pool(), .level = vk::CommandBufferLevel::ePrimary, .commandBufferCount = 1})
            .front());
    fence_ = vk::raii::Fence(dev, vk::FenceCreateInfo{});
}

std::unique_ptr<ComputeKernel> WalkRunner::make_kernel(const uint32_t* spv, size_t bytes) {
    auto& dev = ctx_.device();
    // indexed by binding (WALK_BINDING_*, kernel_interface.glsl)
    std::vector<vk::DescriptorType> types(WALK_BINDINGS, vk::DescriptorType::eStorageBuffer);
    types[WALK_BINDING_STACK] = stack_type_;
    auto k = std::make_unique<ComputeKernel>(dev, spv, bytes, types, uint32_t(sizeof(WalkPush)));
    std::vector<const Buffer*> bound(WALK_BINDINGS);
    bound[WALK_BINDING_STACK] = &stack_;
    bound[WALK_BINDING_STAGING] = &staging_;
    bound[WALK_BINDING_ENERGY] = &energy_;
    bound[WALK_BINDING_ANGLES] = &angles_;
    k->bind(dev, bound);
    return k;
}

void WalkRunner::clear() {
    ctx_.run_now([&](vk::CommandBuffer c) {
        vk::MemoryBarrier before{.srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferRead,
                                 .dstAccessMask = vk::AccessFlagBits::eTransferWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer,
                          vk::PipelineStageFlagBits::eTransfer, {}, before, nullptr, nullptr);
        c.fillBuffer(*staging_.buffer, 0, VK_WHOLE_SIZE, 0);
        c.fillBuffer(*totals_.buffer, 0, VK_WHOLE_SIZE, 0);
        c.fillBuffer(*energy_.buffer, 0, VK_WHOLE_SIZE, 0);
        vk::MemoryBarrier after{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                                                 vk::AccessFlagBits::eTransferWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                          vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer, {}, after,
                          nullptr, nullptr);
    });
    std::memset(host_.mapped, 0, configs_ * (values_ + ENERGY_ENTRIES) * 8);
}

void WalkRunner::transfer(bool upload) {   // host <-> (totals, energy), waiting for it
    const vk::DeviceSize totals_bytes = configs_ * values_ * 8, energy_bytes = configs_ * ENERGY_ENTRIES * 8;
    ctx_.run_now([&](vk::CommandBuffer c) {
        vk::MemoryBarrier before{
            .srcAccessMask =
                vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eHostWrite | vk::AccessFlagBits::eTransferWrite,
            .dstAccessMask = vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eTransferWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eHost |
                              vk::PipelineStageFlagBits::eTransfer,
                          vk::PipelineStageFlagBits::eTransfer, {}, before, nullptr, nullptr);
        if (upload) {
            c.copyBuffer(*host_.buffer, *totals_.buffer, vk::BufferCopy{0, 0, totals_bytes});
            c.copyBuffer(*host_.buffer, *energy_.buffer, vk::BufferCopy{totals_bytes, 0, energy_bytes});
        } else {
            c.copyBuffer(*totals_.buffer, *host_.buffer, vk::BufferCopy{0, 0, totals_bytes});
            c.copyBuffer(*energy_.buffer, *host_.buffer, vk::BufferCopy{0, totals_bytes, energy_bytes});
        }
        vk::MemoryBarrier after{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                .dstAccessMask = vk::AccessFlagBits::eHostRead | vk::AccessFlagBits::eShaderRead |
                                                 vk::AccessFlagBits::eShaderWrite};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                          vk::PipelineStageFlagBits::eHost | vk::PipelineStageFlagBits::eComputeShader, {}, after,
                          nullptr, nullptr);
    });
}

void WalkRunner::upload() { transfer(true); }
void WalkRunner::read_back() { transfer(false); }

AngleResult WalkRunner::angle(size_t config, uint64_t paths, size_t values) const {
    AngleResult a;
    a.paths = paths;
    const uint64_t* t = host_totals_ + config * values_;
    a.raw.assign(t, t + (values ? values : values_));
    std::memcpy(a.energy, host_energy_ + config * ENERGY_ENTRIES, sizeof(a.energy));
    return a;
}

vk::CommandBuffer WalkRunner::begin() {
    cb_.reset();
    cb_.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    return *cb_;
}

void WalkRunner::record_start_timer(vk::CommandBuffer c) {
    c.resetQueryPool(*queries_, 0, 2);
    c.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries_, 0);
}

void WalkRunner::record_stop_timer(vk::CommandBuffer c) {
    c.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries_, 1);
}

void WalkRunner::record_walk(vk::CommandBuffer c, const ComputeKernel& k, const WalkPush& pc, uint32_t groups,
                             uint32_t configs) {
    c.bindPipeline(vk::PipelineBindPoint::eCompute, k.pipeline());
    c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, k.layout(), 0, {*k.set}, nullptr);
    c.pushConstants<WalkPush>(k.layout(), vk::ShaderStageFlagBits::eCompute, 0, pc);
    c.dispatch(groups, configs, 1);
}

void WalkRunner::record_barrier(vk::CommandBuffer c) {
    // the walk's atomics, the fold and the copies to the host touch what the next dispatch touches
    vk::MemoryBarrier b{.srcAccessMask = vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferRead |
                                         vk::AccessFlagBits::eTransferWrite,
                        .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
    c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer,
                      vk::PipelineStageFlagBits::eComputeShader, {}, b, nullptr, nullptr);
}

void WalkRunner::record_fold(vk::CommandBuffer c, uint64_t staging_values, uint32_t shift) {
    gonio::record_fold(c, *fold_, staging_values, shift);
}

void WalkRunner::record_copy_to_host(vk::CommandBuffer c, size_t values) {
    vk::MemoryBarrier to_copy{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                              .dstAccessMask = vk::AccessFlagBits::eTransferRead};
    c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eTransfer, {}, to_copy,
                      nullptr, nullptr);
    c.copyBuffer(*totals_.buffer, *host_.buffer, vk::BufferCopy{0, 0, values * 8});
    c.copyBuffer(*energy_.buffer, *host_.buffer,
                 vk::BufferCopy{0, configs_ * values_ * 8, configs_ * ENERGY_ENTRIES * 8});
    vk::MemoryBarrier to_host{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                              .dstAccessMask = vk::AccessFlagBits::eHostRead};
    c.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eHost, {}, to_host, nullptr,
                      nullptr);
}

void WalkRunner::submit() {
    cb_.end();
    ctx_.device().resetFences(*fence_);
    vk::CommandBuffer h = *cb_;
    ctx_.queue().submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &h}, *fence_);
}

bool WalkRunner::done() { return fence_.getStatus() == vk::Result::eSuccess; }

void WalkRunner::wait() {
    while (ctx_.device().waitForFences(*fence_, VK_TRUE, 1000000000ull) == vk::Result::eTimeout) {}
}

double WalkRunner::timer_seconds() {
    auto [qr, ts] = queries_.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                  vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
    return double(ts[1] - ts[0]) * ctx_.timestamp_period_ns() * 1e-9;
}

double WalkRunner::run(const ComputeKernel& k, const WalkPush& pc, uint32_t groups, uint32_t configs, uint32_t shift,
                       bool fold_after, bool fold_before) {
    vk::CommandBuffer c = begin();
    record_start_timer(c);
    if (fold_before) {
        record_barrier(c);
        record_fold(c, configs_ * values_ / 2, shift);
        record_barrier(c);
    }
    record_walk(c, k, pc, groups, configs);
    if (fold_after) {
        record_barrier(c);
        record_fold(c, configs_ * values_ / 2, shift);
    }
    record_stop_timer(c);
    vk::MemoryBarrier mb{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                         .dstAccessMask = vk::AccessFlagBits::eHostRead | vk::AccessFlagBits::eShaderRead |
                                          vk::AccessFlagBits::eShaderWrite};
    c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                      vk::PipelineStageFlagBits::eHost | vk::PipelineStageFlagBits::eComputeShader, {}, mb, nullptr,
                      nullptr);
    submit();
    wait();
    return timer_seconds();
}

void WalkRunner::fold_now(uint32_t shift) {
    ctx_.run_now([&](vk::CommandBuffer c) {
        record_barrier(c);
        record_fold(c, configs_ * values_ / 2, shift);
        vk::MemoryBarrier mb{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                             .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                                              vk::AccessFlagBits::eTransferRead};
        c.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                          vk::PipelineStageFlagBits::eComputeShader | vk::PipelineStageFlagBits::eTransfer, {}, mb,
                          nullptr, nullptr);
    });
}

}   // namespace gonio
