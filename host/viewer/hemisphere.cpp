#include "hemisphere.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "hemisphere_frag_spv.h"
#include "hemisphere_vert_spv.h"

namespace gonio::view {

namespace {

struct Push {   // hemisphere.vert / .frag
    float rect[4];
    float params[4];
    uint32_t offsets[4];
    uint32_t modes[4];
};
static_assert(sizeof(Push) == 64);

}   // namespace

HemisphereRenderer::HemisphereRenderer(VkContext& ctx, vk::RenderPass pass, uint32_t slots, uint32_t n_theta,
                                       uint32_t n_phi, double dtheta_deg, double dphi_deg)
    : ctx_(ctx),
      n_theta_(n_theta),
      n_phi_(n_phi),
      dtheta_(float(dtheta_deg * M_PI / 180.0)),
      dphi_(float(dphi_deg * M_PI / 180.0)) {
    auto& dev = ctx.device();
    vk::DescriptorSetLayoutBinding b{.binding = 0,
                                     .descriptorType = vk::DescriptorType::eStorageBuffer,
                                     .descriptorCount = 1,
                                     .stageFlags = vk::ShaderStageFlagBits::eFragment};
    set_layout_ =
        vk::raii::DescriptorSetLayout(dev, vk::DescriptorSetLayoutCreateInfo{.bindingCount = 1, .pBindings = &b});
    vk::PushConstantRange pcr{.stageFlags = vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment,
                              .offset = 0,
                              .size = sizeof(Push)};
    vk::DescriptorSetLayout sl = *set_layout_;
    layout_ = vk::raii::PipelineLayout(
        dev, vk::PipelineLayoutCreateInfo{
                 .setLayoutCount = 1, .pSetLayouts = &sl, .pushConstantRangeCount = 1, .pPushConstantRanges = &pcr});
    vk::raii::ShaderModule vert(
        dev, vk::ShaderModuleCreateInfo{.codeSize = sizeof(hemisphere_vert_spv), .pCode = hemisphere_vert_spv});
    vk::raii::ShaderModule frag(
        dev, vk::ShaderModuleCreateInfo{.codeSize = sizeof(hemisphere_frag_spv), .pCode = hemisphere_frag_spv});
    vk::PipelineShaderStageCreateInfo stages[2] = {
        {.stage = vk::ShaderStageFlagBits::eVertex, .module = *vert, .pName = "main"},
        {.stage = vk::ShaderStageFlagBits::eFragment, .module = *frag, .pName = "main"}};
    vk::PipelineVertexInputStateCreateInfo vin{};
    vk::PipelineInputAssemblyStateCreateInfo ia{.topology = vk::PrimitiveTopology::eTriangleList};
    vk::PipelineViewportStateCreateInfo vp{.viewportCount = 1, .scissorCount = 1};
    vk::PipelineRasterizationStateCreateInfo rs{.polygonMode = vk::PolygonMode::eFill,
                                                .cullMode = vk::CullModeFlagBits::eNone,
                                                .frontFace = vk::FrontFace::eCounterClockwise,
                                                .lineWidth = 1.0f};
    vk::PipelineMultisampleStateCreateInfo ms{.rasterizationSamples = vk::SampleCountFlagBits::e1};
    vk::PipelineColorBlendAttachmentState att{
        .blendEnable = VK_FALSE,
        .colorWriteMask = vk::ColorComponentFlagBits::eR | vk::ColorComponentFlagBits::eG |
                          vk::ColorComponentFlagBits::eB | vk::ColorComponentFlagBits::eA};
    vk::PipelineColorBlendStateCreateInfo cbs{.attachmentCount = 1, .pAttachments = &att};
    vk::DynamicState dyn[2] = {vk::DynamicState::eViewport, vk::DynamicState::eScissor};
    vk::PipelineDynamicStateCreateInfo ds{.dynamicStateCount = 2, .pDynamicStates = dyn};
    pipeline_ = vk::raii::Pipeline(dev, nullptr,
                                   vk::GraphicsPipelineCreateInfo{.stageCount = 2,
                                                                  .pStages = stages,
                                                                  .pVertexInputState = &vin,
                                                                  .pInputAssemblyState = &ia,
                                                                  .pViewportState = &vp,
                                                                  .pRasterizationState = &rs,
                                                                  .pMultisampleState = &ms,
                                                                  .pColorBlendState = &cbs,
                                                                  .pDynamicState = &ds,
                                                                  .layout = *layout_,
                                                                  .renderPass = pass,
                                                                  .subpass = 0});
    vk::DescriptorPoolSize size{.type = vk::DescriptorType::eStorageBuffer, .descriptorCount = slots};
    pool_ = vk::raii::DescriptorPool(
        dev, vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                          .maxSets = slots,
                                          .poolSizeCount = 1,
                                          .pPoolSizes = &size});
    std::vector<vk::DescriptorSetLayout> layouts(slots, *set_layout_);
    vk::raii::DescriptorSets sets(
        dev, vk::DescriptorSetAllocateInfo{
                 .descriptorPool = *pool_, .descriptorSetCount = slots, .pSetLayouts = layouts.data()});
    for (auto& s : sets) sets_.push_back(std::move(s));
    buffers_.resize(slots);
    for (uint32_t i = 0; i < slots; ++i) colours(i, size_t(n_theta) * n_phi);
}

HemisphereRenderer::~HemisphereRenderer() = default;

uint32_t* HemisphereRenderer::colours(uint32_t slot, size_t count, bool* fresh) {
    Buffer& b = buffers_.at(slot);
    if (fresh) *fresh = false;
    if (!*b.buffer || b.size < count * sizeof(uint32_t)) {
        if (fresh) *fresh = true;
        b = ctx_.make_buffer(std::max<size_t>(count, 1) * sizeof(uint32_t), vk::BufferUsageFlagBits::eStorageBuffer,
                             true);
        vk::DescriptorBufferInfo info{.buffer = *b.buffer, .offset = 0, .range = VK_WHOLE_SIZE};
        ctx_.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *sets_[slot],
                                                                  .dstBinding = 0,
                                                                  .descriptorCount = 1,
                                                                  .descriptorType = vk::DescriptorType::eStorageBuffer,
                                                                  .pBufferInfo = &info},
                                           nullptr);
    }
    return static_cast<uint32_t*>(b.mapped);
}

void HemisphereRenderer::upload(uint32_t slot, const std::vector<uint32_t>& rgba, uint64_t version) {
    if (uploaded_.size() <= slot) uploaded_.resize(slot + 1, ~0ull);
    bool fresh = false;
    uint32_t* dst = colours(slot, rgba.size(), &fresh);
    if (!fresh && uploaded_[slot] == version) return;
    std::memcpy(dst, rgba.data(), rgba.size() * sizeof(uint32_t));
    uploaded_[slot] = version;
}

void HemisphereRenderer::add(ImDrawList* list, ImVec2 p0, ImVec2 p1, const HemisphereParams& p) {
    panels_.push_back(Panel{p, p0, p1, this});
    list->AddCallback(&HemisphereRenderer::callback, &panels_.back());
    list->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
}

void HemisphereRenderer::begin_render(vk::CommandBuffer cb, vk::Extent2D extent, uint32_t slot,
                                      const ImDrawData* data) {
    cb_ = cb;
    extent_ = extent;
    slot_ = slot;
    display_pos_ = data->DisplayPos;
    scale_ = data->FramebufferScale;
}

void HemisphereRenderer::end_frame() { panels_.clear(); }

void HemisphereRenderer::callback(const ImDrawList*, const ImDrawCmd* cmd) {
    const Panel* p = static_cast<const Panel*>(cmd->UserCallbackData);
    p->self->draw(cmd, p->params, p->p0, p->p1);
}

void HemisphereRenderer::draw(const ImDrawCmd* cmd, const HemisphereParams& p, ImVec2 p0, ImVec2 p1) {
    if (extent_.width == 0 || extent_.height == 0) return;
    // framebuffer pixels of the panel and of the clip rectangle
    auto fx = [&](float x) { return (x - display_pos_.x) * scale_.x; };
    auto fy = [&](float y) { return (y - display_pos_.y) * scale_.y; };
    float cx0 = std::max({fx(cmd->ClipRect.x), fx(p0.x), 0.0f}), cy0 = std::max({fy(cmd->ClipRect.y), fy(p0.y), 0.0f});
    float cx1 = std::min({fx(cmd->ClipRect.z), fx(p1.x), float(extent_.width)});
    float cy1 = std::min({fy(cmd->ClipRect.w), fy(p1.y), float(extent_.height)});
    if (cx1 - cx0 < 1.0f || cy1 - cy0 < 1.0f) return;
    vk::Viewport vp{0.0f, 0.0f, float(extent_.width), float(extent_.height), 0.0f, 1.0f};
    vk::Rect2D sc{{int32_t(cx0), int32_t(cy0)}, {uint32_t(cx1 - cx0), uint32_t(cy1 - cy0)}};
    Push pc{};
    pc.rect[0] = 2.0f * fx(p0.x) / float(extent_.width) - 1.0f;
    pc.rect[1] = 2.0f * fy(p0.y) / float(extent_.height) - 1.0f;
    pc.rect[2] = 2.0f * fx(p1.x) / float(extent_.width) - 1.0f;
    pc.rect[3] = 2.0f * fy(p1.y) / float(extent_.height) - 1.0f;
    pc.params[0] = p.light;
    pc.params[1] = dtheta_;
    pc.params[2] = dphi_;
    pc.params[3] = p.light_phi;
    pc.offsets[0] = p.offset;
    pc.offsets[1] = n_theta_;
    pc.offsets[2] = n_phi_;
    cb_.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_);
    cb_.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *layout_, 0, {*sets_[slot_]}, nullptr);
    cb_.setViewport(0, vp);
    cb_.setScissor(0, sc);
    cb_.pushConstants<Push>(*layout_, vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment, 0, pc);
    cb_.draw(6, 1, 0, 0);
}

}   // namespace gonio::view
