// vk_context.h: the Vulkan instance, the chosen compute device, and buffers. Nothing here knows physics.
#pragma once
#include <vulkan/vulkan_raii.hpp>

#include <atomic>
#include <functional>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct DeviceInfo {
    uint32_t index;
    std::string name;
    std::string type;   // "discrete GPU", "CPU", ...
    std::string driver;   // driver name and info
    uint32_t api_version;
    bool usable;   // has what gonio needs (compute queue, 64-bit integer atomics)
    std::string why_not;   // when !usable
};

struct ContextOptions {
    int device_index = -1;   // -1: pick automatically (discrete > integrated > virtual > CPU)
    bool validation = false;   // enable VK_LAYER_KHRONOS_validation; every message is counted and printed
    // For a window (the viewer): extra instance and device extensions, and a test a queue family must also
    // pass (presentation support). Devices without such a family are skipped as unusable.
    std::vector<std::string> instance_extensions;
    std::vector<std::string> device_extensions;
    std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)> queue_filter;
};

// A device buffer plus, where the device memory is not host-visible, a staging buffer for transfers.
struct Buffer {
    vk::raii::Buffer buffer = nullptr;
    vk::raii::DeviceMemory memory = nullptr;
    vk::DeviceSize size = 0;
    void* mapped = nullptr;   // non-null when the memory is host-visible
};

class VkContext {
public:
    explicit VkContext(const ContextOptions& opt);
    ~VkContext();

    static std::vector<DeviceInfo> list_devices();   // does not need a context
    const DeviceInfo& device_info() const { return info_; }
    std::string driver_string() const;

    vk::raii::Instance& instance() { return instance_; }
    vk::raii::Device& device() { return device_; }
    vk::raii::PhysicalDevice& physical() { return physical_; }
    vk::Queue queue() const { return *queue_; }
    uint32_t queue_family() const { return family_; }
    float timestamp_period_ns() const { return timestamp_period_; }

    // Host-visible, mapped buffer (uniforms, uploads and readbacks); device-local too when the device has
    // such memory and prefer_device_local is set.
    Buffer make_buffer(vk::DeviceSize size, vk::BufferUsageFlags usage, bool prefer_device_local);
    // Device-local buffer, not mapped: where the atomics go (a discrete GPU's atomics must not cross the bus).
    // Usable as a transfer source and destination.
    Buffer make_device_buffer(vk::DeviceSize size, vk::BufferUsageFlags usage);

    // Record and run a one-off command buffer, waiting for it.
    template <class F>
    void run_now(F&& record) {
        vk::raii::CommandBuffer cb = std::move(
            vk::raii::CommandBuffers(
                device_, {.commandPool = *pool_, .level = vk::CommandBufferLevel::ePrimary, .commandBufferCount = 1})
                .front());
        cb.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
        record(*cb);
        cb.end();
        submit_and_wait(*cb);
    }
    void submit_and_wait(vk::CommandBuffer cb);
    vk::raii::CommandPool& pool() { return pool_; }

    // Validation messages seen so far (warnings and errors); tests require zero.
    uint64_t validation_messages() const { return validation_count_.load(); }

private:
    vk::raii::Context context_;
    vk::raii::Instance instance_ = nullptr;
    vk::raii::DebugUtilsMessengerEXT messenger_ = nullptr;
    vk::raii::PhysicalDevice physical_ = nullptr;
    vk::raii::Device device_ = nullptr;
    vk::raii::Queue queue_ = nullptr;
    vk::raii::CommandPool pool_ = nullptr;
    vk::raii::Fence fence_ = nullptr;
    uint32_t family_ = 0;
    float timestamp_period_ = 1.0f;
    DeviceInfo info_;
    std::atomic<uint64_t> validation_count_{0};
    friend VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                         VkDebugUtilsMessageTypeFlagsEXT,
                                                         const VkDebugUtilsMessengerCallbackDataEXT*, void*);
};

}   // namespace gonio
