// reference_gpu.cpp: runs shaders/simulate.comp through Vulkan.
#include "reference.h"
#include "progress.h"
#include "stack_gpu.h"
#include "vk_context.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "simulate_spv.h"

namespace gonio {

namespace {

struct Push {
    uint32_t path_base_lo, path_base_hi, path_count, seed, stream, max_events, n_theta, n_phi;
    float sin_ti, cos_ti, inv_dtheta, inv_dphi;
};
static_assert(sizeof(Push) == 48);

constexpr uint32_t kLocalSize = 64;     // local_size_x in simulate.comp

struct SpecData {
    VkBool32 specialised;
    uint32_t layer_count, base_kind, rough_mask, absorb_mask;
    VkBool32 orders;
    uint32_t paths_per_invocation;
};

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
    if (!divides(o.dtheta_deg, 90.0)) throw std::invalid_argument("--dtheta must divide 90 degrees into a whole number of bins");
    if (!divides(o.dphi_deg, 180.0)) throw std::invalid_argument("--dphi must divide 180 degrees into a whole number of bins");
    if (o.max_events < 1) throw std::invalid_argument("--max-events must be at least 1");
    // lavapipe silently ends every loop of an invocation after 65535 iterations in total (docs/PHYSICS.md).
    if (uint64_t(o.paths_per_invocation) * (uint64_t(o.max_events) + 2) + o.paths_per_invocation + 8 >= 65535)
        throw std::invalid_argument("--max-events " + std::to_string(o.max_events) + " is too large: paths per invocation (" +
                                    std::to_string(o.paths_per_invocation) + ") x (max events + 2) must stay below 65535");
}

SimResult simulate_gpu(VkContext& ctx, const Stack& stack, const SimOptions& opt) {
    validate_options(opt);
    validate_stack(stack);
    SimResult res;
    res.stack = stack;
    res.options = opt;
    res.device = ctx.device_info().name;
    res.driver = ctx.driver_string();
    res.n_theta = uint32_t(std::lround(90.0 / opt.dtheta_deg));
    res.n_phi = uint32_t(std::lround(360.0 / opt.dphi_deg));
    res.n_classes = opt.orders ? 3 : 1;
    const size_t n_values = size_t(res.n_classes) * 2 * res.n_theta * res.n_phi * 6;

    auto& dev = ctx.device();
    StackGpu sg = pack_stack(stack);
    WalkSpec ws = walk_spec(stack, opt.specialised);

    Buffer ubo = ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true);
    std::memcpy(ubo.mapped, &sg, sizeof(sg));
    Buffer hist = ctx.make_buffer(n_values * 8, vk::BufferUsageFlagBits::eStorageBuffer, true);
    Buffer energy = ctx.make_buffer(9 * 8, vk::BufferUsageFlagBits::eStorageBuffer, true);

    // descriptor set layout, pipeline layout
    std::array<vk::DescriptorSetLayoutBinding, 3> binds{{
        {.binding = 0, .descriptorType = vk::DescriptorType::eUniformBuffer, .descriptorCount = 1, .stageFlags = vk::ShaderStageFlagBits::eCompute},
        {.binding = 1, .descriptorType = vk::DescriptorType::eStorageBuffer, .descriptorCount = 1, .stageFlags = vk::ShaderStageFlagBits::eCompute},
        {.binding = 2, .descriptorType = vk::DescriptorType::eStorageBuffer, .descriptorCount = 1, .stageFlags = vk::ShaderStageFlagBits::eCompute}}};
    vk::raii::DescriptorSetLayout dsl(dev, vk::DescriptorSetLayoutCreateInfo{}.setBindings(binds));
    vk::PushConstantRange pcr{.stageFlags = vk::ShaderStageFlagBits::eCompute, .offset = 0, .size = sizeof(Push)};
    vk::DescriptorSetLayout dsl_h = *dsl;
    vk::raii::PipelineLayout layout(dev, vk::PipelineLayoutCreateInfo{}.setSetLayouts(dsl_h).setPushConstantRanges(pcr));

    std::array<vk::DescriptorPoolSize, 2> sizes{{{.type = vk::DescriptorType::eUniformBuffer, .descriptorCount = 1}, {.type = vk::DescriptorType::eStorageBuffer, .descriptorCount = 2}}};
    vk::raii::DescriptorPool dpool(dev, vk::DescriptorPoolCreateInfo{}
        .setFlags(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet).setMaxSets(1).setPoolSizes(sizes));
    vk::raii::DescriptorSets sets(dev, vk::DescriptorSetAllocateInfo{}.setDescriptorPool(*dpool).setSetLayouts(dsl_h));
    vk::raii::DescriptorSet& set = sets.front();
    vk::DescriptorBufferInfo bi0{.buffer = *ubo.buffer, .offset = 0, .range = VK_WHOLE_SIZE}, bi1{.buffer = *hist.buffer, .offset = 0, .range = VK_WHOLE_SIZE}, bi2{.buffer = *energy.buffer, .offset = 0, .range = VK_WHOLE_SIZE};
    std::array<vk::WriteDescriptorSet, 3> writes{{
        vk::WriteDescriptorSet{}.setDstSet(*set).setDstBinding(0).setDescriptorType(vk::DescriptorType::eUniformBuffer).setBufferInfo(bi0),
        vk::WriteDescriptorSet{}.setDstSet(*set).setDstBinding(1).setDescriptorType(vk::DescriptorType::eStorageBuffer).setBufferInfo(bi1),
        vk::WriteDescriptorSet{}.setDstSet(*set).setDstBinding(2).setDescriptorType(vk::DescriptorType::eStorageBuffer).setBufferInfo(bi2)}};
    dev.updateDescriptorSets(writes, nullptr);

    // pipeline, specialised to the stack
    vk::raii::ShaderModule module(dev, vk::ShaderModuleCreateInfo{}.setCodeSize(sizeof(simulate_spv)).setPCode(simulate_spv));
    SpecData sd{ws.specialised ? VK_TRUE : VK_FALSE, ws.layer_count, ws.base_kind, ws.rough_mask, ws.absorb_mask,
                opt.orders ? VK_TRUE : VK_FALSE, opt.paths_per_invocation};
    std::array<vk::SpecializationMapEntry, 7> entries{{
        {0, offsetof(SpecData, specialised), sizeof(VkBool32)}, {1, offsetof(SpecData, layer_count), 4},
        {2, offsetof(SpecData, base_kind), 4}, {3, offsetof(SpecData, rough_mask), 4},
        {4, offsetof(SpecData, absorb_mask), 4}, {5, offsetof(SpecData, orders), sizeof(VkBool32)},
        {6, offsetof(SpecData, paths_per_invocation), 4}}};
    vk::SpecializationInfo spec{.mapEntryCount = uint32_t(entries.size()), .pMapEntries = entries.data(), .dataSize = sizeof(sd), .pData = &sd};
    vk::PipelineShaderStageCreateInfo stage{.stage = vk::ShaderStageFlagBits::eCompute, .module = *module, .pName = "main", .pSpecializationInfo = &spec};
    vk::raii::Pipeline pipeline(dev, nullptr, vk::ComputePipelineCreateInfo{.stage = stage, .layout = *layout});

    vk::raii::QueryPool queries(dev, vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
    vk::raii::CommandBuffer cb = std::move(vk::raii::CommandBuffers(dev, {.commandPool = *ctx.pool(), .level = vk::CommandBufferLevel::ePrimary, .commandBufferCount = 1}).front());

    const uint64_t per_group = uint64_t(kLocalSize) * opt.paths_per_invocation;
    const uint64_t max_batch = 65535ull * per_group;
    uint64_t batch = opt.batch_paths ? std::min<uint64_t>(opt.batch_paths, max_batch) : std::min<uint64_t>(1u << 16, max_batch);

    Progress progress(opt.progress, stack.name, opt.paths * opt.theta_i_deg.size());
    uint64_t done_all = 0;
    for (size_t a = 0; a < opt.theta_i_deg.size(); ++a) {
        AngleResult ar;
        ar.theta_i_deg = opt.theta_i_deg[a];
        ar.paths = opt.paths;
        std::memset(hist.mapped, 0, n_values * 8);
        std::memset(energy.mapped, 0, 9 * 8);
        double ti = opt.theta_i_deg[a] * M_PI / 180.0;
        Push pc{};
        pc.seed = opt.seed;
        pc.stream = uint32_t(a);
        pc.max_events = opt.max_events;
        pc.n_theta = res.n_theta;
        pc.n_phi = res.n_phi;
        pc.sin_ti = float(std::sin(ti));
        pc.cos_ti = float(std::cos(ti));
        pc.inv_dtheta = float(180.0 / (M_PI * opt.dtheta_deg));
        pc.inv_dphi = float(180.0 / (M_PI * opt.dphi_deg));
        auto t0 = std::chrono::steady_clock::now();
        uint64_t done = 0;
        while (done < opt.paths) {
            uint64_t n = std::min(batch, opt.paths - done);
            pc.path_base_lo = uint32_t(done);
            pc.path_base_hi = uint32_t(done >> 32);
            pc.path_count = uint32_t(n);
            uint32_t groups = uint32_t((n + per_group - 1) / per_group);
            cb.reset();
            cb.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
            cb.resetQueryPool(*queries, 0, 2);
            cb.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries, 0);
            cb.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline);
            cb.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout, 0, {*set}, nullptr);
            cb.pushConstants<Push>(*layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
            cb.dispatch(groups, 1, 1);
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
            progress.update(done_all, a, opt.theta_i_deg.size(), opt.theta_i_deg[a]);
            // adapt the batch towards ~0.25 s per submission (results do not depend on it)
            if (!opt.batch_paths && dt > 0.0) {
                double target = double(n) * 0.25 / dt;
                uint64_t next = uint64_t(std::clamp(target, double(per_group), double(n) * 4.0));
                batch = std::min<uint64_t>(std::max<uint64_t>(next / per_group, 1) * per_group, max_batch);
            }
        }
        ar.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ar.raw.assign(static_cast<const uint64_t*>(hist.mapped), static_cast<const uint64_t*>(hist.mapped) + n_values);
        std::memcpy(ar.energy, energy.mapped, sizeof(ar.energy));
        res.angles.push_back(std::move(ar));
    }
    progress.finish();
    return res;
}

}  // namespace gonio
