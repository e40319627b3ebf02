// validation.h: the exit status that checks after a run give: the Khronos validation layer's messages (--validate),
// and numbers of the JSON written that were not finite.
#pragma once
#include "vk_context.h"

namespace gonio {

// 1 (after saying how many) if the validation layer reported anything, else 0.
int check_validation(const VkContext& ctx);
// 1 (after saying how many, a bug to report) if a JSON file written so far held numbers that were not finite (they
// are written as null), else 0. `what`: the files, for the message.
int check_finite_json(const char* what = "summary.json");

}   // namespace gonio
