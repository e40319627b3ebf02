// compute_kernel.h: a compute pipeline with its descriptor set (one binding per buffer, in order),
// push-constant block and specialisation.
#pragma once
#include "cpu_twin.h"
#include "kernel_interface.glsl"
#include "vk_context.h"

#include <algorithm>
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

// The specialisation constants of the walk kernels (simulate.comp, simulate_batch.comp; ids SPEC_* in
// kernel_interface.glsl), from the stack's WalkSpec: builds `k`'s pipeline. baked (simulate.comp only): the baked
// stack, the stack's parameters compiled into the pipeline as well (stack_constants.glsl; can_bake_stack says where
// they apply). invalid_path_for_tests: a path whose weight is made NaN, for the tests.
inline void build_walk_kernel(ComputeKernel& k, vk::raii::Device& dev, const WalkSpec& ws, bool orders,
                              uint32_t paths_per_invocation, const StackGpu* baked = nullptr,
                              uint32_t invalid_path_for_tests = 0xffffffffu) {
    struct SpecData {
        VkBool32 specialised;
        uint32_t layer_count, base_kind, rough_mask, absorb_mask, scatter_mask;
        VkBool32 orders;
        uint32_t paths_per_invocation;
        VkBool32 series;
        VkBool32 baked_stack;
        uint32_t baked_sides;
        float layer[2][BAKED_LAYER_FLOATS];   // p0.xyzw, tau.xyz, c0.xyz, c1.xyz
        float series_values[BAKED_SERIES_FLOATS];   // gain.xyzw, lost.xyz, emit.xyzw
        uint32_t invalid_path;
    } sd{};
    sd.specialised = ws.specialised ? VK_TRUE : VK_FALSE;
    sd.layer_count = ws.layer_count;
    sd.base_kind = ws.base_kind;
    sd.rough_mask = ws.rough_mask;
    sd.absorb_mask = ws.absorb_mask;
    sd.scatter_mask = ws.scatter_mask;
    sd.orders = orders ? VK_TRUE : VK_FALSE;
    sd.paths_per_invocation = paths_per_invocation;
    sd.series = ws.series ? VK_TRUE : VK_FALSE;
    std::vector<vk::SpecializationMapEntry> entries{
        {SPEC_SPECIALISED, offsetof(SpecData, specialised), sizeof(VkBool32)},
        {SPEC_LAYER_COUNT, offsetof(SpecData, layer_count), 4},
        {SPEC_BASE_KIND, offsetof(SpecData, base_kind), 4},
        {SPEC_ROUGH_MASK, offsetof(SpecData, rough_mask), 4},
        {SPEC_ABSORB_MASK, offsetof(SpecData, absorb_mask), 4},
        {SPEC_SCATTER_MASK, offsetof(SpecData, scatter_mask), 4},
        {SPEC_ORDERS, offsetof(SpecData, orders), sizeof(VkBool32)},
        {SPEC_PATHS_PER_INVOCATION, offsetof(SpecData, paths_per_invocation), 4},
        {SPEC_SERIES, offsetof(SpecData, series), sizeof(VkBool32)}};
    if (baked) {
        sd.baked_stack = VK_TRUE;
        sd.baked_sides = uint32_t(baked->info.y);
        for (int l = 0; l < 2; ++l) {
            const LayerGpu& L = baked->layers[l];
            const float v[BAKED_LAYER_FLOATS] = {L.p0.x, L.p0.y, L.p0.z, L.p0.w, L.tau.x, L.tau.y, L.tau.z,
                                                 L.c0.x, L.c0.y, L.c0.z, L.c1.x, L.c1.y,  L.c1.z};
            std::copy(v, v + BAKED_LAYER_FLOATS, sd.layer[l]);
        }
        const SeriesGpu& S = baked->series;
        const float v[BAKED_SERIES_FLOATS] = {S.gain.x, S.gain.y, S.gain.z, S.gain.w, S.lost.x, S.lost.y,
                                              S.lost.z, S.emit.x, S.emit.y, S.emit.z, S.emit.w};
        std::copy(v, v + BAKED_SERIES_FLOATS, sd.series_values);
        entries.push_back({SPEC_BAKED_STACK, offsetof(SpecData, baked_stack), sizeof(VkBool32)});
        entries.push_back({SPEC_BAKED_SIDES, offsetof(SpecData, baked_sides), 4});
        for (uint32_t i = 0; i < 2 * BAKED_LAYER_FLOATS; ++i)
            entries.push_back({SPEC_BAKED_LAYERS + i, uint32_t(offsetof(SpecData, layer) + 4 * i), 4});
        for (uint32_t i = 0; i < BAKED_SERIES_FLOATS; ++i)
            entries.push_back({SPEC_BAKED_SERIES + i, uint32_t(offsetof(SpecData, series_values) + 4 * i), 4});
    }
    if (invalid_path_for_tests != 0xffffffffu) {
        sd.invalid_path = invalid_path_for_tests;
        entries.push_back({SPEC_INVALID_PATH_FOR_TESTS, offsetof(SpecData, invalid_path), 4});
    }
    k.build(dev, entries, &sd, sizeof(sd));
}

}   // namespace gonio
