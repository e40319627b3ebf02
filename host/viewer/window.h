// window.h: the viewer's window (GLFW) and what presents to it (Vulkan surface, swapchain, render pass,
// frames in flight), including reading a presented frame back for a screenshot. Knows nothing of gonio.
#pragma once
#include "vk_context.h"

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace gonio::view {

// GLFW, initialised once per process; throws std::runtime_error (no display, no Vulkan loader) with advice.
class Window {
public:
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;
    GLFWwindow* glfw() const { return window_; }
    bool should_close() const;
    void request_close();
    void set_size(int width, int height);
    void framebuffer_size(int& width, int& height) const;

    // What a VkContext needs to present to GLFW windows (instance extensions, queue family test).
    static std::vector<std::string> instance_extensions();
    static bool can_present(VkInstance instance, VkPhysicalDevice device, uint32_t family);

private:
    GLFWwindow* window_ = nullptr;
};

// One frame being recorded: the command buffer is inside the render pass, which clears to the background.
struct Frame {
    vk::CommandBuffer cb;
    vk::Extent2D extent;
    uint32_t slot = 0;   // frame in flight: 0 .. Presenter::kFramesInFlight - 1
    uint32_t image = 0;
};

class Presenter {
public:
    static constexpr uint32_t kFramesInFlight = 2;
    Presenter(VkContext& ctx, Window& window);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    vk::RenderPass render_pass() const { return *render_pass_; }
    vk::Format format() const { return format_; }
    vk::Instance instance() const;

    // Waits for the slot, acquires an image and begins the render pass. false: nothing to draw now (the
    // window is minimised or has no pixels, or the swapchain was just rebuilt); try again next frame.
    bool begin(Frame& f);
    // Ends the render pass, submits and presents. With capture, the image is read back after rendering and
    // available from take_capture (RGBA8, top row first).
    void end(Frame& f, bool capture);
    bool take_capture(std::vector<uint8_t>& rgba, uint32_t& width, uint32_t& height);
    void wait_idle();

private:
    void rebuild();
    void destroy_swapchain();

    VkContext& ctx_;
    Window& window_;
    vk::raii::SurfaceKHR surface_ = nullptr;
    vk::Format format_ = vk::Format::eUndefined;
    vk::ColorSpaceKHR colour_space_{};
    vk::PresentModeKHR present_mode_ = vk::PresentModeKHR::eFifo;
    bool can_capture_ = false;
    vk::raii::RenderPass render_pass_ = nullptr;
    vk::raii::SwapchainKHR swapchain_ = nullptr;
    vk::Extent2D extent_{0, 0};
    std::vector<vk::Image> images_;
    std::vector<vk::raii::ImageView> views_;
    std::vector<vk::raii::Framebuffer> framebuffers_;
    std::vector<vk::raii::Semaphore> rendered_;   // per swapchain image
    vk::raii::CommandPool pool_ = nullptr;
    struct Slot {
        vk::raii::CommandBuffer cb = nullptr;
        vk::raii::Fence fence = nullptr;
        vk::raii::Semaphore acquired = nullptr;
    };
    std::vector<Slot> slots_;
    uint32_t next_slot_ = 0;
    bool rebuild_needed_ = true;
    Buffer capture_;
    vk::Extent2D capture_extent_{0, 0};
    bool capture_ready_ = false;
};

}   // namespace gonio::view
