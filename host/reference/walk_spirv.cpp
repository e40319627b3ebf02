#include "walk_spirv.h"

#include "simulate_batch_s0m0_spv.h"
#include "simulate_batch_s0m1_spv.h"
#include "simulate_batch_s1m0_spv.h"
#include "simulate_batch_s1m1_spv.h"
#include "simulate_s0m0_spv.h"
#include "simulate_s0m1_spv.h"
#include "simulate_s1m0_spv.h"
#include "simulate_s1m1_spv.h"

namespace gonio {

namespace {

template <size_t N>
Spirv spirv(const uint32_t (&words)[N]) {
    return {words, sizeof(words)};
}

}   // namespace

Spirv walk_spirv(const WalkSpec& spec, WalkShader shader) {
    const bool statistics = spec.microsurface_mask != 0, multiple = spec.multiple_mask != 0;
    if (shader == WalkShader::batch) {
        if (statistics) return multiple ? spirv(simulate_batch_s1m1_spv) : spirv(simulate_batch_s1m0_spv);
        return multiple ? spirv(simulate_batch_s0m1_spv) : spirv(simulate_batch_s0m0_spv);
    }
    if (statistics) return multiple ? spirv(simulate_s1m1_spv) : spirv(simulate_s1m0_spv);
    return multiple ? spirv(simulate_s0m1_spv) : spirv(simulate_s0m0_spv);
}

}   // namespace gonio
