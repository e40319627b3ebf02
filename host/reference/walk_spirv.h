// The walk's SPIR-V for a run: the variant of simulate.comp or simulate_batch.comp (CMakeLists.txt) that carries the
// microsurface statistics and the walk on the microsurface only where the spec's stacks have them. The code a
// specialisation constant folds away still costs lavapipe's JIT its time before it folds (shaders/lib/microsurface.glsl).
#pragma once

#include <cstddef>
#include <cstdint>

#include "stack_gpu.h"

namespace gonio {

struct Spirv {
    const uint32_t* words;
    size_t bytes;
};

enum class WalkShader { one_stack, batch };   // simulate.comp, simulate_batch.comp

// spec: the walk's specialisation (for a batch, its stacks' masks ORed)
Spirv walk_spirv(const WalkSpec& spec, WalkShader shader);

}   // namespace gonio
