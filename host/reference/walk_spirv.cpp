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
constexpr Spirv spirv(const uint32_t (&words)[N]) {
    return {words, sizeof(words)};
}

// [batch][statistics][multiple]
constexpr Spirv kVariants[2][2][2] = {
    {{spirv(simulate_s0m0_spv), spirv(simulate_s0m1_spv)}, {spirv(simulate_s1m0_spv), spirv(simulate_s1m1_spv)}},
    {{spirv(simulate_batch_s0m0_spv), spirv(simulate_batch_s0m1_spv)},
     {spirv(simulate_batch_s1m0_spv), spirv(simulate_batch_s1m1_spv)}}};

}   // namespace

Spirv walk_spirv(const WalkSpec& spec, WalkShader shader) {
    return kVariants[shader == WalkShader::batch][spec.microsurface_mask != 0][spec.multiple_mask != 0];
}

}   // namespace gonio
