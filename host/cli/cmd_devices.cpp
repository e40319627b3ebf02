#include "cmd_devices.h"
#include "vk_context.h"

#include <cstdio>
#include <exception>

namespace gonio {

namespace {

int run_devices(NoSettings&, const std::vector<std::string>&) {
    auto devs = VkContext::list_devices();
    if (devs.empty()) {
        std::printf("no Vulkan devices\n");
        return 1;
    }
    int chosen = -1;
    try {
        VkContext ctx({});
        chosen = int(ctx.device_info().index);
    } catch (const std::exception& e) { std::fprintf(stderr, "gonio: %s\n", e.what()); }
    for (auto& d : devs) {
        std::printf("%c %u: %s (%s; %s; Vulkan %u.%u)%s%s\n", int(d.index) == chosen ? '*' : ' ', d.index,
                    d.name.c_str(), d.type.c_str(), d.driver.c_str(), VK_API_VERSION_MAJOR(d.api_version),
                    VK_API_VERSION_MINOR(d.api_version),
                    d.usable ? "" : "  [unusable: ", d.usable ? "" : (d.why_not + "]").c_str());
    }
    return chosen >= 0 ? 0 : 1;
}

}   // namespace

Command devices_command() {
    return {"devices", "", "list Vulkan devices; '*' marks the one gonio uses", "",
            invocation(&no_options, &run_devices)};
}

}   // namespace gonio
