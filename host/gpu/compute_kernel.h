// compute_kernel.h: a compute pipeline with its descriptor set (one binding per buffer, in order),
// push-constant block and specialisation.
#pragma once
#include "pipeline_keeper.h"
#include "vk_context.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <future>
#include <thread>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

// A compute pipeline with its descriptor set (one binding per buffer, in order) and push-constant block.
struct ComputeKernel {
    vk::raii::ShaderModule module = nullptr;
    std::shared_ptr<const KernelLayouts> layouts;   // kept and shared where the device keeps pipelines
    vk::raii::DescriptorPool pool = nullptr;
    vk::raii::DescriptorSet set = nullptr;
    std::shared_ptr<const vk::raii::Pipeline> pipeline_;   // likewise
    std::vector<vk::DescriptorType> types;
    std::string key;   // the bindings, push constants and SPIR-V (pipeline_keeper.h)

    vk::Pipeline pipeline() const { return **pipeline_; }
    vk::PipelineLayout layout() const { return *layouts->layout; }

    ComputeKernel(vk::raii::Device& dev, const uint32_t* spv, size_t bytes, std::vector<vk::DescriptorType> types_,
                  uint32_t push_bytes)
        : types(std::move(types_)) {
        module = vk::raii::ShaderModule(dev, vk::ShaderModuleCreateInfo{}.setCodeSize(bytes).setPCode(spv));
        std::vector<vk::DescriptorSetLayoutBinding> binds;
        std::vector<vk::DescriptorPoolSize> sizes;
        for (uint32_t i = 0; i < types.size(); ++i) {
            binds.push_back({.binding = i,
                             .descriptorType = types[i],
                             .descriptorCount = 1,
                             .stageFlags = vk::ShaderStageFlagBits::eCompute});
            sizes.push_back({.type = types[i], .descriptorCount = 1});
            key += std::to_string(int(types[i])) + ",";
        }
        key += "push " + std::to_string(push_bytes);
        layouts = kernel_layouts(*dev, key, [&] {
            KernelLayouts k;
            k.set_layout = vk::raii::DescriptorSetLayout(dev, vk::DescriptorSetLayoutCreateInfo{}.setBindings(binds));
            vk::PushConstantRange pcr{.stageFlags = vk::ShaderStageFlagBits::eCompute, .offset = 0, .size = push_bytes};
            vk::DescriptorSetLayout h = *k.set_layout;
            k.layout = vk::raii::PipelineLayout(
                dev, vk::PipelineLayoutCreateInfo{}.setSetLayouts(h).setPushConstantRanges(pcr));
            return k;
        });
        key += " spirv ";
        key.append(reinterpret_cast<const char*>(spv), bytes);
        vk::DescriptorSetLayout h = *layouts->set_layout;
        pool = vk::raii::DescriptorPool(dev, vk::DescriptorPoolCreateInfo{}
                                                 .setFlags(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet)
                                                 .setMaxSets(1)
                                                 .setPoolSizes(sizes));
        set = std::move(
            vk::raii::DescriptorSets(dev, vk::DescriptorSetAllocateInfo{}.setDescriptorPool(*pool).setSetLayouts(h))
                .front());
    }
    // buffers[i] goes to binding i, as types[i] (the *_BINDING_* constants of kernel_interface.glsl say which is which)
    void bind(vk::raii::Device& dev, std::vector<const Buffer*> buffers) {
        if (buffers.size() != types.size())
            throw std::logic_error("ComputeKernel::bind: " + std::to_string(buffers.size()) + " buffers for " +
                                   std::to_string(types.size()) + " bindings");
        for (size_t i = 0; i < buffers.size(); ++i)
            if (!buffers[i]) throw std::logic_error("ComputeKernel::bind: no buffer for binding " + std::to_string(i));
        std::vector<vk::DescriptorBufferInfo> infos;
        for (auto* b : buffers) infos.push_back({.buffer = *b->buffer, .offset = 0, .range = VK_WHOLE_SIZE});
        std::vector<vk::WriteDescriptorSet> writes;
        for (uint32_t i = 0; i < infos.size(); ++i)
            writes.push_back(
                vk::WriteDescriptorSet{}.setDstSet(*set).setDstBinding(i).setDescriptorType(types[i]).setBufferInfo(
                    infos[i]));
        dev.updateDescriptorSets(writes, nullptr);
    }
    void build(vk::raii::Device& dev, const std::vector<vk::SpecializationMapEntry>& entries, const void* data,
               size_t bytes) {
        vk::SpecializationInfo spec{
            .mapEntryCount = uint32_t(entries.size()), .pMapEntries = entries.data(), .dataSize = bytes, .pData = data};
        vk::PipelineShaderStageCreateInfo stage{.stage = vk::ShaderStageFlagBits::eCompute,
                                                .module = *module,
                                                .pName = "main",
                                                .pSpecializationInfo = entries.empty() ? nullptr : &spec};
        std::string spec_key = key + " spec ";
        for (const vk::SpecializationMapEntry& e : entries)
            spec_key +=
                std::to_string(e.constantID) + ":" + std::to_string(e.offset) + ":" + std::to_string(e.size) + ",";
        spec_key.append(static_cast<const char*>(data), data ? bytes : 0);
        pipeline_ = kernel_pipeline(*dev, spec_key, [&] {
            return vk::raii::Pipeline(dev, nullptr,
                                      vk::ComputePipelineCreateInfo{.stage = stage, .layout = *layouts->layout});
        });
    }
    // Records one dispatch of groups x 1 x 1 workgroups: the pipeline, its descriptor set and push constants `push`.
    template <class Push>
    void record(vk::CommandBuffer c, const Push& push, uint32_t groups) const {
        c.bindPipeline(vk::PipelineBindPoint::eCompute, pipeline());
        c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, layout(), 0, {*set}, nullptr);
        c.pushConstants<Push>(layout(), vk::ShaderStageFlagBits::eCompute, 0, push);
        c.dispatch(groups, 1, 1);
    }
};

// Workgroups of `size` invocations that cover n invocations.
inline uint32_t groups_for(size_t n, uint32_t size) { return uint32_t((n + size - 1) / size); }

// A memory barrier: what stage `from` did with access `src` is visible to stage `to` for access `dst`.
inline void barrier(vk::CommandBuffer c, vk::PipelineStageFlags from, vk::AccessFlags src, vk::PipelineStageFlags to,
                    vk::AccessFlags dst) {
    vk::MemoryBarrier b{.srcAccessMask = src, .dstAccessMask = dst};
    c.pipelineBarrier(from, to, {}, b, nullptr, nullptr);
}
// The common ones: a compute dispatch's writes before the next dispatch reads (or writes) them, before a transfer
// or the host reads them, and a transfer's writes before the host or a dispatch reads them.
inline void barrier_compute_to_compute(vk::CommandBuffer c) {
    barrier(c, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
            vk::PipelineStageFlagBits::eComputeShader,
            vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
}
inline void barrier_compute_to_transfer(vk::CommandBuffer c) {
    barrier(c, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
            vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferRead);
}
inline void barrier_transfer_to_host(vk::CommandBuffer c) {
    barrier(c, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
            vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
}
inline void barrier_compute_to_host(vk::CommandBuffer c) {   // a dispatch's writes to host-visible memory
    barrier(c, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
            vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
}
inline void barrier_transfer_to_compute(vk::CommandBuffer c) {
    barrier(c, vk::PipelineStageFlagBits::eTransfer, vk::AccessFlagBits::eTransferWrite,
            vk::PipelineStageFlagBits::eComputeShader,
            vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
}

// Makes n pipelines (or anything) by make(i), i < n, on as many threads as the machine has: vkCreateComputePipelines
// is where lavapipe translates and optimises a shader, on the calling thread; each pipeline must own its objects
// (module, layout, descriptor pool), so that no object is shared between the threads. A worker's exception is
// rethrown.
inline void make_concurrently(size_t n, const std::function<void(size_t)>& make) {
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next++) < n;) make(i);
    };
    const unsigned threads = std::min<unsigned>(std::max(1u, std::thread::hardware_concurrency()), unsigned(n));
    std::vector<std::future<void>> pool;
    for (unsigned t = 1; t < threads; ++t) pool.push_back(std::async(std::launch::async, work));
    work();
    for (auto& f : pool) f.get();
}

}   // namespace gonio
