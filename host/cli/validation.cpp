#include "validation.h"

#include <cstdio>

namespace gonio {

int check_validation(const VkContext& ctx) {
    if (ctx.validation_messages() > 0) {
        std::fprintf(stderr, "gonio: %llu Vulkan validation message(s): failing\n",
                     (unsigned long long)ctx.validation_messages());
        return 1;
    }
    return 0;
}

}   // namespace gonio
