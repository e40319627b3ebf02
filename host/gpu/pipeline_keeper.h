// pipeline_keeper.h: compute pipelines kept for a device's life and handed to every kernel that asks for the same one
// (the same SPIR-V, bindings, push constants and specialisation), where a process runs one run after another on one
// device: the Python module (host/python), whose runs would otherwise have lavapipe compile every pipeline again. A
// device keeps them only where keep_pipelines named it; the command line's do not. Kept objects are never destroyed
// (the module's contexts live as long as the process).
#pragma once
#include <vulkan/vulkan_raii.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

namespace gonio {

// A kernel's layouts: its descriptor set's and its pipeline's.
struct KernelLayouts {
    vk::raii::DescriptorSetLayout set_layout = nullptr;
    vk::raii::PipelineLayout layout = nullptr;
};

// From now on the device keeps its kernels' layouts and pipelines.
void keep_pipelines(VkDevice device);
// The layouts of `key` (the bindings and push constants) on `device`: the kept ones, else make() (kept where the
// device keeps them).
std::shared_ptr<const KernelLayouts> kernel_layouts(VkDevice device, const std::string& key,
                                                    const std::function<KernelLayouts()>& make);
// The pipeline of `key` (its layouts' key, its SPIR-V and its specialisation) on `device`, likewise.
std::shared_ptr<const vk::raii::Pipeline> kernel_pipeline(VkDevice device, const std::string& key,
                                                          const std::function<vk::raii::Pipeline()>& make);

}   // namespace gonio
