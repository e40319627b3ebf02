// cmd_devices.h: `gonio devices`: the Vulkan devices, '*' on the one gonio uses.
#pragma once
#include "options.h"

namespace gonio {

Command devices_command();

}   // namespace gonio
