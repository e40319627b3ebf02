#include "validation.h"
#include "json.h"

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

int check_finite_json(const char* what) {
    if (non_finite_json_numbers() == 0) return 0;
    std::fprintf(stderr, "gonio: %llu numbers of %s were not finite (written as null): a bug, please report it\n",
                 (unsigned long long)non_finite_json_numbers(), what);
    return 1;
}

}   // namespace gonio
