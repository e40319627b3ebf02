// validation.h: the exit status of a run under --validate (the Khronos validation layer).
#pragma once
#include "vk_context.h"

namespace gonio {

// 1 (after saying how many) if the validation layer reported anything, else 0.
int check_validation(const VkContext& ctx);

}   // namespace gonio
