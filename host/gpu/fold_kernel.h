// fold_kernel.h: shaders/fold.comp, which adds a dispatch's packed staging histogram (weight and square in one
// 64-bit value per bin and channel) into the 64-bit totals and clears it; used by every walk kernel's host.
#pragma once
#include "compute_kernel.h"

#include <cstdint>
#include <memory>

namespace gonio {

// The fold pipeline bound to (staging, totals); its push constants: FoldPush (kernel_interface.glsl).
std::unique_ptr<ComputeKernel> make_fold_kernel(vk::raii::Device& dev, const Buffer& staging, const Buffer& totals);

// Records the fold of `values` staging values whose weights were scaled by 2^-shift (fold.comp) into c.
void record_fold(vk::CommandBuffer c, const ComputeKernel& fold, uint64_t values, uint32_t shift);

// Workgroups that fold `values` staging values; throws std::invalid_argument beyond a dispatch's 65535.
uint32_t fold_workgroups(uint64_t values);

}   // namespace gonio
