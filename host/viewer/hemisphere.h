// hemisphere.h: draws hemisphere top views (hemisphere.vert/.frag) inside Dear ImGui windows. Dear ImGui 1.86's
// Vulkan backend has no user textures, so a panel is a draw-list callback that runs this pipeline over the
// panel's rectangle; the fragment shader reads the bins straight from a buffer (one per frame in flight).
#pragma once
#include "vk_context.h"

#include <imgui.h>

#include <deque>
#include <vector>

namespace gonio::view {

struct HemisphereParams {
    uint32_t offset = 0;   // first colour of the panel in the frame's buffer (RGBA8 per bin, theta-major)
    float light = -1.0f;   // sin(theta_i) for the light's marker; < 0: none
    float light_phi = 0.0f;   // its azimuth phi_i, radians
};

class HemisphereRenderer {
public:
    HemisphereRenderer(VkContext& ctx, vk::RenderPass pass, uint32_t slots, uint32_t n_theta, uint32_t n_phi,
                       double dtheta_deg, double dphi_deg);
    ~HemisphereRenderer();
    // The colour buffer of a frame slot, at least `count` long; the slot must not be in flight. `fresh` is
    // set when the buffer was (re)made and holds nothing yet.
    uint32_t* colours(uint32_t slot, size_t count, bool* fresh = nullptr);
    // Copies the panels' colours into the slot's buffer unless it holds this version already.
    void upload(uint32_t slot, const std::vector<uint32_t>& rgba, uint64_t version);
    // Adds a panel over [p0, p1] (screen coordinates) to the draw list.
    void add(ImDrawList* list, ImVec2 p0, ImVec2 p1, const HemisphereParams& p);
    // Before ImGui_ImplVulkan_RenderDrawData: where the callbacks record.
    void begin_render(vk::CommandBuffer cb, vk::Extent2D extent, uint32_t slot, const ImDrawData* data);
    void end_frame();   // forget this frame's panels

private:
    static void callback(const ImDrawList* list, const ImDrawCmd* cmd);
    void draw(const ImDrawCmd* cmd, const HemisphereParams& p, ImVec2 p0, ImVec2 p1);
    struct Panel {
        HemisphereParams params;
        ImVec2 p0, p1;
        HemisphereRenderer* self;
    };

    VkContext& ctx_;
    uint32_t n_theta_, n_phi_;
    float dtheta_, dphi_;
    vk::raii::DescriptorSetLayout set_layout_ = nullptr;
    vk::raii::PipelineLayout layout_ = nullptr;
    vk::raii::Pipeline pipeline_ = nullptr;
    vk::raii::DescriptorPool pool_ = nullptr;
    std::vector<vk::raii::DescriptorSet> sets_;
    std::vector<Buffer> buffers_;
    std::vector<uint64_t> uploaded_;
    std::deque<Panel> panels_;
    vk::CommandBuffer cb_{};
    vk::Extent2D extent_{};
    uint32_t slot_ = 0;
    ImVec2 display_pos_{0, 0}, scale_{1, 1};
};

}   // namespace gonio::view
