// compute_kernel.h: a compute pipeline with its descriptor set (one binding per buffer, in order),
// push-constant block and specialisation.
#pragma once
#include "vk_context.h"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace gonio {

// A compute pipeline with its descriptor set (one binding per buffer, in order) and push-constant block.
struct ComputeKernel {
    vk::raii::ShaderModule module = nullptr;
    vk::raii::DescriptorSetLayout set_layout = nullptr;
    vk::raii::PipelineLayout layout = nullptr;
    vk::raii::DescriptorPool pool = nullptr;
    vk::raii::DescriptorSet set = nullptr;
    vk::raii::Pipeline pipeline = nullptr;
    std::vector<vk::DescriptorType> types;

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
        }
        set_layout = vk::raii::DescriptorSetLayout(dev, vk::DescriptorSetLayoutCreateInfo{}.setBindings(binds));
        vk::PushConstantRange pcr{.stageFlags = vk::ShaderStageFlagBits::eCompute, .offset = 0, .size = push_bytes};
        vk::DescriptorSetLayout h = *set_layout;
        layout =
            vk::raii::PipelineLayout(dev, vk::PipelineLayoutCreateInfo{}.setSetLayouts(h).setPushConstantRanges(pcr));
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
        pipeline = vk::raii::Pipeline(dev, nullptr, vk::ComputePipelineCreateInfo{.stage = stage, .layout = *layout});
    }
};

}   // namespace gonio
