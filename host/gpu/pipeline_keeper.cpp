// pipeline_keeper.cpp: see pipeline_keeper.h.
#include "pipeline_keeper.h"

#include <map>
#include <mutex>
#include <set>

namespace gonio {

namespace {

struct Kept {
    std::mutex mutex;
    std::set<VkDevice> devices;
    std::map<std::pair<VkDevice, std::string>, std::shared_ptr<const KernelLayouts>> layouts;
    std::map<std::pair<VkDevice, std::string>, std::shared_ptr<const vk::raii::Pipeline>> pipelines;
};

Kept& kept() {
    static Kept* k = new Kept;   // never destroyed: its objects belong to devices that outlive static destruction
    return *k;
}

// The kept object of `key`, or make()'s, kept where the device keeps them. make() runs outside the lock (lavapipe
// compiles there, and kernels are made on several threads at once); of two made at once, the first kept wins.
template <class T, class Make>
std::shared_ptr<const T> kept_or_made(std::map<std::pair<VkDevice, std::string>, std::shared_ptr<const T>>& kept_map,
                                      VkDevice device, const std::string& key, const Make& make) {
    Kept& k = kept();
    bool keeps = false;
    {
        std::lock_guard<std::mutex> lock(k.mutex);
        keeps = k.devices.count(device) > 0;
        if (keeps) {
            auto it = kept_map.find({device, key});
            if (it != kept_map.end()) return it->second;
        }
    }
    if (!keeps) return std::make_shared<const T>(make());
    auto made = std::make_shared<const T>(make());
    std::lock_guard<std::mutex> lock(k.mutex);
    return kept_map.emplace(std::make_pair(device, key), made).first->second;
}

}   // namespace

void keep_pipelines(VkDevice device) {
    std::lock_guard<std::mutex> lock(kept().mutex);
    kept().devices.insert(device);
}

std::shared_ptr<const KernelLayouts> kernel_layouts(VkDevice device, const std::string& key,
                                                    const std::function<KernelLayouts()>& make) {
    return kept_or_made(kept().layouts, device, key, make);
}

std::shared_ptr<const vk::raii::Pipeline> kernel_pipeline(VkDevice device, const std::string& key,
                                                          const std::function<vk::raii::Pipeline()>& make) {
    return kept_or_made(kept().pipelines, device, key, make);
}

}   // namespace gonio
