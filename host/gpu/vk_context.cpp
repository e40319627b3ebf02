#include "vk_context.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace gonio {

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* ctx = static_cast<VkContext*>(user);
    ctx->validation_count_++;
    std::fprintf(stderr, "gonio: vulkan validation (%s): %s\n",
                 severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
                 data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string type_name(vk::PhysicalDeviceType t) {
    switch (t) {
        case vk::PhysicalDeviceType::eDiscreteGpu:
            return "discrete GPU";
        case vk::PhysicalDeviceType::eIntegratedGpu:
            return "integrated GPU";
        case vk::PhysicalDeviceType::eVirtualGpu:
            return "virtual GPU";
        case vk::PhysicalDeviceType::eCpu:
            return "CPU";
        default:
            return "other";
    }
}

int type_rank(vk::PhysicalDeviceType t) {
    switch (t) {
        case vk::PhysicalDeviceType::eDiscreteGpu:
            return 4;
        case vk::PhysicalDeviceType::eIntegratedGpu:
            return 3;
        case vk::PhysicalDeviceType::eVirtualGpu:
            return 2;
        case vk::PhysicalDeviceType::eCpu:
            return 1;
        default:
            return 0;
    }
}

// A window's queue (ContextOptions::queue_filter) must also draw and present.
struct QueueNeeds {
    const ContextOptions* opt = nullptr;
    VkInstance instance = VK_NULL_HANDLE;
};

int compute_family(const vk::raii::PhysicalDevice& pd, const QueueNeeds& needs = {}) {
    auto fams = pd.getQueueFamilyProperties();
    const bool window = needs.opt && needs.opt->queue_filter;
    for (uint32_t i = 0; i < fams.size(); ++i) {
        if (!(fams[i].queueFlags & vk::QueueFlagBits::eCompute)) continue;
        if (window &&
            (!(fams[i].queueFlags & vk::QueueFlagBits::eGraphics) || !needs.opt->queue_filter(needs.instance, *pd, i)))
            continue;
        return int(i);
    }
    return -1;
}

DeviceInfo describe(const vk::raii::PhysicalDevice& pd, uint32_t index, const QueueNeeds& needs = {}) {
    DeviceInfo d;
    auto chain = pd.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties>();
    const auto& p = chain.get<vk::PhysicalDeviceProperties2>().properties;
    const auto& drv = chain.get<vk::PhysicalDeviceDriverProperties>();
    d.index = index;
    d.name = p.deviceName.data();
    d.type = type_name(p.deviceType);
    d.driver = std::string(drv.driverName.data()) + " " + drv.driverInfo.data();
    d.api_version = p.apiVersion;
    auto feats = pd.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features>();
    bool int64 = feats.get<vk::PhysicalDeviceFeatures2>().features.shaderInt64;
    bool atom64 = feats.get<vk::PhysicalDeviceVulkan12Features>().shaderBufferInt64Atomics;
    d.usable = true;
    if (VK_API_VERSION_MINOR(p.apiVersion) < 2 && VK_API_VERSION_MAJOR(p.apiVersion) == 1) {
        d.usable = false;
        d.why_not = "needs Vulkan 1.2";
    } else if (!int64 || !atom64) {
        d.usable = false;
        d.why_not = "no 64-bit integer buffer atomics (shaderInt64, shaderBufferInt64Atomics)";
    } else if (compute_family(pd) < 0) {
        d.usable = false;
        d.why_not = "no compute queue";
    } else if (needs.opt && needs.opt->queue_filter && compute_family(pd, needs) < 0) {
        d.usable = false;
        d.why_not = "no queue that computes, draws and presents to the window";
    }
    if (d.usable && needs.opt) {
        auto exts = pd.enumerateDeviceExtensionProperties();
        for (const auto& want : needs.opt->device_extensions) {
            bool has = false;
            for (const auto& e : exts) has = has || want == e.extensionName.data();
            if (!has) {
                d.usable = false;
                d.why_not = "no device extension " + want;
                break;
            }
        }
    }
    return d;
}

vk::raii::Instance make_instance(vk::raii::Context& ctx, bool validation, const std::vector<std::string>& extra = {}) {
    vk::ApplicationInfo app{.pApplicationName = "gonio",
                            .applicationVersion = 1,
                            .pEngineName = "gonio",
                            .engineVersion = 1,
                            .apiVersion = VK_API_VERSION_1_2};
    std::vector<const char*> layers, exts;
    if (validation) {
        bool found = false;
        for (auto& l : ctx.enumerateInstanceLayerProperties())
            if (std::strcmp(l.layerName, kValidationLayer) == 0) found = true;
        if (!found)
            throw std::runtime_error(
                "validation requested but VK_LAYER_KHRONOS_validation is not installed "
                "(Debian: apt-get install vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    for (const auto& e : extra) exts.push_back(e.c_str());
    // With validation, synchronization validation too: barriers that happen to suffice on lavapipe (one
    // coherent memory type, in-order execution) must also be right for a real GPU.
    vk::ValidationFeatureEnableEXT enables[] = {vk::ValidationFeatureEnableEXT::eSynchronizationValidation};
    vk::ValidationFeaturesEXT features{.enabledValidationFeatureCount = 1, .pEnabledValidationFeatures = enables};
    vk::InstanceCreateInfo ci{.pNext = validation ? &features : nullptr,
                              .pApplicationInfo = &app,
                              .enabledLayerCount = uint32_t(layers.size()),
                              .ppEnabledLayerNames = layers.data(),
                              .enabledExtensionCount = uint32_t(exts.size()),
                              .ppEnabledExtensionNames = exts.data()};
    return vk::raii::Instance(ctx, ci);
}

}   // namespace

std::vector<DeviceInfo> VkContext::list_devices() {
    vk::raii::Context ctx;
    vk::raii::Instance inst = make_instance(ctx, false);
    std::vector<DeviceInfo> out;
    vk::raii::PhysicalDevices pds(inst);
    for (uint32_t i = 0; i < pds.size(); ++i) out.push_back(describe(pds[i], i));
    return out;
}

VkContext::VkContext(const ContextOptions& opt) {
    instance_ = make_instance(context_, opt.validation, opt.instance_extensions);
    const QueueNeeds needs{&opt, *instance_};
    if (opt.validation) {
        vk::DebugUtilsMessengerCreateInfoEXT mci{
            .messageSeverity =
                vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning | vk::DebugUtilsMessageSeverityFlagBitsEXT::eError,
            .messageType = vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral |
                           vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation |
                           vk::DebugUtilsMessageTypeFlagBitsEXT::ePerformance,
            .pfnUserCallback = reinterpret_cast<PFN_vkDebugUtilsMessengerCallbackEXT>(&debug_callback),
            .pUserData = this};
        messenger_ = vk::raii::DebugUtilsMessengerEXT(instance_, mci);
    }
    vk::raii::PhysicalDevices pds(instance_);
    if (pds.empty()) throw std::runtime_error("no Vulkan device found (Debian: apt-get install mesa-vulkan-drivers)");
    int chosen = -1;
    if (opt.device_index >= 0) {
        if (size_t(opt.device_index) >= pds.size())
            throw std::runtime_error("--device " + std::to_string(opt.device_index) + ": there are only " +
                                     std::to_string(pds.size()) + " devices (see `gonio devices`)");
        DeviceInfo d = describe(pds[opt.device_index], opt.device_index, needs);
        if (!d.usable)
            throw std::runtime_error("device " + std::to_string(opt.device_index) + " (" + d.name +
                                     ") cannot run gonio: " + d.why_not);
        chosen = opt.device_index;
    } else {
        int best = -1;
        for (uint32_t i = 0; i < pds.size(); ++i) {
            DeviceInfo d = describe(pds[i], i, needs);
            if (!d.usable) continue;
            int r = type_rank(pds[i].getProperties().deviceType);
            if (r > best) {
                best = r;
                chosen = int(i);
            }
        }
        if (chosen < 0) throw std::runtime_error("no Vulkan device can run gonio (see `gonio devices`)");
    }
    physical_ = std::move(pds[chosen]);
    info_ = describe(physical_, uint32_t(chosen), needs);
    family_ = uint32_t(compute_family(physical_, needs));
    timestamp_period_ = physical_.getProperties().limits.timestampPeriod;

    float prio = 1.0f;
    vk::DeviceQueueCreateInfo qci{.queueFamilyIndex = family_, .queueCount = 1, .pQueuePriorities = &prio};
    vk::StructureChain<vk::DeviceCreateInfo, vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features> chain;
    chain.get<vk::DeviceCreateInfo>().setQueueCreateInfos(qci);
    std::vector<const char*> dev_exts;
    for (const auto& e : opt.device_extensions) dev_exts.push_back(e.c_str());
    chain.get<vk::DeviceCreateInfo>().setPEnabledExtensionNames(dev_exts);
    chain.get<vk::PhysicalDeviceFeatures2>().features.shaderInt64 = VK_TRUE;
    chain.get<vk::PhysicalDeviceVulkan12Features>().shaderBufferInt64Atomics = VK_TRUE;
    device_ = vk::raii::Device(physical_, chain.get<vk::DeviceCreateInfo>());
    queue_ = vk::raii::Queue(device_, family_, 0);
    pool_ = vk::raii::CommandPool(
        device_, {.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer, .queueFamilyIndex = family_});
    fence_ = vk::raii::Fence(device_, vk::FenceCreateInfo{});
}

VkContext::~VkContext() {
    if (*device_) device_.waitIdle();
}

std::string VkContext::driver_string() const { return info_.driver; }

Buffer VkContext::make_buffer(vk::DeviceSize size, vk::BufferUsageFlags usage, bool prefer_device_local) {
    Buffer b;
    b.size = size;
    b.buffer = vk::raii::Buffer(device_, {.size = size, .usage = usage, .sharingMode = vk::SharingMode::eExclusive});
    auto req = b.buffer.getMemoryRequirements();
    auto props = physical_.getMemoryProperties();
    auto want_base = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
    int type = -1;
    for (int pass = prefer_device_local ? 0 : 1; pass < 2 && type < 0; ++pass) {
        auto want = pass == 0 ? want_base | vk::MemoryPropertyFlagBits::eDeviceLocal : want_base;
        for (uint32_t i = 0; i < props.memoryTypeCount; ++i) {
            if (!(req.memoryTypeBits & (1u << i))) continue;
            if ((props.memoryTypes[i].propertyFlags & want) != want) continue;
            if (props.memoryHeaps[props.memoryTypes[i].heapIndex].size < req.size) continue;
            type = int(i);
            break;
        }
    }
    if (type < 0)
        throw std::runtime_error("no host-visible memory type for a buffer of " + std::to_string(size) + " bytes");
    b.memory = vk::raii::DeviceMemory(device_, {.allocationSize = req.size, .memoryTypeIndex = uint32_t(type)});
    b.buffer.bindMemory(*b.memory, 0);
    b.mapped = b.memory.mapMemory(0, VK_WHOLE_SIZE);
    return b;
}

Buffer VkContext::make_device_buffer(vk::DeviceSize size, vk::BufferUsageFlags usage) {
    Buffer b;
    b.size = size;
    b.buffer = vk::raii::Buffer(
        device_, {.size = size,
                  .usage = usage | vk::BufferUsageFlagBits::eTransferSrc | vk::BufferUsageFlagBits::eTransferDst,
                  .sharingMode = vk::SharingMode::eExclusive});
    auto req = b.buffer.getMemoryRequirements();
    auto props = physical_.getMemoryProperties();
    int type = -1;
    for (uint32_t i = 0; i < props.memoryTypeCount && type < 0; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (props.memoryTypes[i].propertyFlags & vk::MemoryPropertyFlagBits::eDeviceLocal))
            type = int(i);
    for (uint32_t i = 0; i < props.memoryTypeCount && type < 0; ++i)   // no device-local type at all: any
        if (req.memoryTypeBits & (1u << i)) type = int(i);
    if (type < 0) throw std::runtime_error("no memory type for a device buffer of " + std::to_string(size) + " bytes");
    b.memory = vk::raii::DeviceMemory(device_, {.allocationSize = req.size, .memoryTypeIndex = uint32_t(type)});
    b.buffer.bindMemory(*b.memory, 0);
    return b;
}

void VkContext::submit_and_wait(vk::CommandBuffer cb) {
    device_.resetFences(*fence_);
    vk::SubmitInfo si{.commandBufferCount = 1, .pCommandBuffers = &cb};
    queue_.submit(si, *fence_);
    while (device_.waitForFences(*fence_, VK_TRUE, 1000000000ull) == vk::Result::eTimeout) {}
}

}   // namespace gonio
