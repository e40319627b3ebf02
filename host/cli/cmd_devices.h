// cmd_devices.h: `gonio devices`: the Vulkan devices, '*' on the one gonio uses.
#pragma once

namespace gonio {

int cmd_devices();

}   // namespace gonio
