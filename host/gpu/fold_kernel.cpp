// fold_kernel.cpp: see fold_kernel.h.
#include "fold_kernel.h"
#include "kernel_interface.glsl"

#include <stdexcept>

#include "fold_spv.h"

namespace gonio {

std::unique_ptr<ComputeKernel> make_fold_kernel(vk::raii::Device& dev, const Buffer& staging, const Buffer& totals) {
    // both storage buffers, indexed by binding (FOLD_BINDING_*, kernel_interface.glsl)
    auto k = std::make_unique<ComputeKernel>(
        dev, fold_spv, sizeof(fold_spv),
        std::vector<vk::DescriptorType>(FOLD_BINDINGS, vk::DescriptorType::eStorageBuffer), uint32_t(sizeof(FoldPush)));
    std::vector<const Buffer*> bound(FOLD_BINDINGS);
    bound[FOLD_BINDING_STAGING] = &staging;
    bound[FOLD_BINDING_TOTALS] = &totals;
    k->bind(dev, bound);
    k->build(dev, {}, nullptr, 0);
    return k;
}

void record_fold(vk::CommandBuffer c, const ComputeKernel& fold, uint64_t values, uint32_t shift) {
    FoldPush push{};
    push.count = uint32_t(values);
    push.shift = shift;
    c.bindPipeline(vk::PipelineBindPoint::eCompute, fold.pipeline());
    c.bindDescriptorSets(vk::PipelineBindPoint::eCompute, fold.layout(), 0, {*fold.set}, nullptr);
    c.pushConstants<FoldPush>(fold.layout(), vk::ShaderStageFlagBits::eCompute, 0, push);
    c.dispatch(fold_workgroups(values), 1, 1);
}

uint32_t fold_workgroups(uint64_t values) {
    const uint64_t per_group = uint64_t(FOLD_LOCAL_SIZE) * FOLD_PER_INVOCATION;   // kernel_interface.glsl
    uint64_t groups = (values + per_group - 1) / per_group;
    if (groups > 65535 || values > 0xffffffffull)
        throw std::invalid_argument(
            "too many bins (x stacks) for one fold dispatch: use wider --dtheta / --dphi or a smaller batch");
    return uint32_t(groups);
}

}   // namespace gonio
