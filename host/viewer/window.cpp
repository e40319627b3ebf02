#include "window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace gonio::view {

namespace {

std::string g_glfw_error;

void glfw_error(int code, const char* what) {
    g_glfw_error = std::string(what ? what : "") + " (GLFW error " + std::to_string(code) + ")";
}

void init_glfw_once() {
    static bool done = false;
    if (done) return;
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit())
        throw std::runtime_error("cannot open a window: " + g_glfw_error +
                                 ". gonio-view needs a display (DISPLAY or WAYLAND_DISPLAY); without one, run it under "
                                 "xvfb-run -a (Debian: apt-get install xvfb xauth)");
    if (!glfwVulkanSupported())
        throw std::runtime_error(
            "GLFW finds no Vulkan loader (Debian: apt-get install libvulkan1 mesa-vulkan-drivers)");
    std::atexit(glfwTerminate);
    done = true;
}

}   // namespace

Window::Window(int width, int height, const std::string& title) {
    init_glfw_once();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) throw std::runtime_error("cannot create the window: " + g_glfw_error);
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }
void Window::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::set_size(int width, int height) { glfwSetWindowSize(window_, width, height); }
void Window::framebuffer_size(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

std::vector<std::string> Window::instance_extensions() {
    init_glfw_once();
    uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    if (!names) throw std::runtime_error("GLFW cannot present with Vulkan here: " + g_glfw_error);
    return std::vector<std::string>(names, names + n);
}

bool Window::can_present(VkInstance instance, VkPhysicalDevice device, uint32_t family) {
    return glfwGetPhysicalDevicePresentationSupport(instance, device, family) == GLFW_TRUE;
}

Presenter::Presenter(VkContext& ctx, Window& window) : ctx_(ctx), window_(window) {
    VkSurfaceKHR s = VK_NULL_HANDLE;
    VkResult r = glfwCreateWindowSurface(*ctx.instance(), window.glfw(), nullptr, &s);
    if (r != VK_SUCCESS) throw std::runtime_error("cannot create a Vulkan surface for the window: " + g_glfw_error);
    surface_ = vk::raii::SurfaceKHR(ctx.instance(), s);
    if (!ctx.physical().getSurfaceSupportKHR(ctx.queue_family(), *surface_))
        throw std::runtime_error("the device's queue cannot present to this window");

    // 8-bit UNORM (Dear ImGui's colours are meant for it), either channel order
    auto formats = ctx.physical().getSurfaceFormatsKHR(*surface_);
    if (formats.empty()) throw std::runtime_error("the surface offers no formats");
    vk::SurfaceFormatKHR chosen = formats.front();
    for (auto want : {vk::Format::eB8G8R8A8Unorm, vk::Format::eR8G8B8A8Unorm}) {
        auto it = std::find_if(formats.begin(), formats.end(), [&](const vk::SurfaceFormatKHR& f) {
            return f.format == want && f.colorSpace == vk::ColorSpaceKHR::eSrgbNonlinear;
        });
        if (it != formats.end()) {
            chosen = *it;
            break;
        }
    }
    format_ = chosen.format;
    colour_space_ = chosen.colorSpace;
    // FIFO (always there). Measured under Xvfb: IMMEDIATE and MAILBOX are no faster (the copy to the X server
    // and the rendering dominate), and the viewer paces itself by its reference slices.
    present_mode_ = vk::PresentModeKHR::eFifo;
    vk::AttachmentDescription colour{.format = format_,
                                     .samples = vk::SampleCountFlagBits::e1,
                                     .loadOp = vk::AttachmentLoadOp::eClear,
                                     .storeOp = vk::AttachmentStoreOp::eStore,
                                     .stencilLoadOp = vk::AttachmentLoadOp::eDontCare,
                                     .stencilStoreOp = vk::AttachmentStoreOp::eDontCare,
                                     .initialLayout = vk::ImageLayout::eUndefined,
                                     .finalLayout = vk::ImageLayout::ePresentSrcKHR};
    vk::AttachmentReference ref{.attachment = 0, .layout = vk::ImageLayout::eColorAttachmentOptimal};
    vk::SubpassDescription sub{
        .pipelineBindPoint = vk::PipelineBindPoint::eGraphics, .colorAttachmentCount = 1, .pColorAttachments = &ref};
    vk::SubpassDependency dep{.srcSubpass = VK_SUBPASS_EXTERNAL,
                              .dstSubpass = 0,
                              .srcStageMask = vk::PipelineStageFlagBits::eColorAttachmentOutput,
                              .dstStageMask = vk::PipelineStageFlagBits::eColorAttachmentOutput,
                              .srcAccessMask = {},
                              .dstAccessMask = vk::AccessFlagBits::eColorAttachmentWrite};
    render_pass_ = vk::raii::RenderPass(ctx.device(), vk::RenderPassCreateInfo{.attachmentCount = 1,
                                                                               .pAttachments = &colour,
                                                                               .subpassCount = 1,
                                                                               .pSubpasses = &sub,
                                                                               .dependencyCount = 1,
                                                                               .pDependencies = &dep});
    pool_ = vk::raii::CommandPool(ctx.device(), {.flags = vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                                 .queueFamilyIndex = ctx.queue_family()});
    vk::raii::CommandBuffers cbs(
        ctx.device(),
        {.commandPool = *pool_, .level = vk::CommandBufferLevel::ePrimary, .commandBufferCount = kFramesInFlight});
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
        Slot s;
        s.cb = std::move(cbs[i]);
        s.fence = vk::raii::Fence(ctx.device(), {.flags = vk::FenceCreateFlagBits::eSignaled});
        s.acquired = vk::raii::Semaphore(ctx.device(), vk::SemaphoreCreateInfo{});
        slots_.push_back(std::move(s));
    }
}

Presenter::~Presenter() { wait_idle(); }

vk::Instance Presenter::instance() const { return *ctx_.instance(); }

void Presenter::wait_idle() { ctx_.device().waitIdle(); }

void Presenter::destroy_swapchain() {
    framebuffers_.clear();
    views_.clear();
    images_.clear();
}

void Presenter::rebuild() {
    ctx_.device().waitIdle();
    auto caps = ctx_.physical().getSurfaceCapabilitiesKHR(*surface_);
    vk::Extent2D ext = caps.currentExtent;
    if (ext.width == 0xFFFFFFFFu) {
        int w = 0, h = 0;
        window_.framebuffer_size(w, h);
        ext.width = std::clamp(uint32_t(std::max(w, 0)), caps.minImageExtent.width, caps.maxImageExtent.width);
        ext.height = std::clamp(uint32_t(std::max(h, 0)), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    destroy_swapchain();
    if (ext.width == 0 || ext.height == 0) {   // minimised: keep asking
        swapchain_ = nullptr;
        extent_ = vk::Extent2D{0, 0};
        rebuild_needed_ = true;
        return;
    }
    uint32_t count = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);
    vk::ImageUsageFlags usage = vk::ImageUsageFlagBits::eColorAttachment;
    can_capture_ = bool(caps.supportedUsageFlags & vk::ImageUsageFlagBits::eTransferSrc);
    if (can_capture_) usage |= vk::ImageUsageFlagBits::eTransferSrc;
    vk::SwapchainCreateInfoKHR ci{.surface = *surface_,
                                  .minImageCount = count,
                                  .imageFormat = format_,
                                  .imageColorSpace = colour_space_,
                                  .imageExtent = ext,
                                  .imageArrayLayers = 1,
                                  .imageUsage = usage,
                                  .imageSharingMode = vk::SharingMode::eExclusive,
                                  .preTransform = caps.currentTransform,
                                  .compositeAlpha = vk::CompositeAlphaFlagBitsKHR::eOpaque,
                                  .presentMode = present_mode_,
                                  .clipped = VK_TRUE,
                                  .oldSwapchain = *swapchain_ ? *swapchain_ : vk::SwapchainKHR{}};
    if (!(caps.supportedCompositeAlpha & vk::CompositeAlphaFlagBitsKHR::eOpaque))
        ci.compositeAlpha = vk::CompositeAlphaFlagBitsKHR(uint32_t(caps.supportedCompositeAlpha) &
                                                          -uint32_t(caps.supportedCompositeAlpha));
    vk::raii::SwapchainKHR fresh(ctx_.device(), ci);
    swapchain_ = std::move(fresh);
    extent_ = ext;
    images_ = swapchain_.getImages();
    rendered_.clear();
    for (vk::Image img : images_) {
        views_.emplace_back(ctx_.device(),
                            vk::ImageViewCreateInfo{.image = img,
                                                    .viewType = vk::ImageViewType::e2D,
                                                    .format = format_,
                                                    .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}});
        vk::ImageView v = *views_.back();
        framebuffers_.emplace_back(ctx_.device(), vk::FramebufferCreateInfo{.renderPass = *render_pass_,
                                                                            .attachmentCount = 1,
                                                                            .pAttachments = &v,
                                                                            .width = ext.width,
                                                                            .height = ext.height,
                                                                            .layers = 1});
        rendered_.emplace_back(ctx_.device(), vk::SemaphoreCreateInfo{});
    }
    rebuild_needed_ = false;
}

bool Presenter::begin(Frame& f) {
    int w = 0, h = 0;
    window_.framebuffer_size(w, h);
    if (!rebuild_needed_ && (uint32_t(w) != extent_.width || uint32_t(h) != extent_.height)) rebuild_needed_ = true;
    if (rebuild_needed_) {
        rebuild();
        if (rebuild_needed_) return false;
    }
    Slot& s = slots_[next_slot_];
    while (ctx_.device().waitForFences(*s.fence, VK_TRUE, 1000000000ull) == vk::Result::eTimeout) {}
    uint32_t image = 0;
    try {
        auto [res, idx] = swapchain_.acquireNextImage(UINT64_MAX, *s.acquired);
        if (res != vk::Result::eSuccess && res != vk::Result::eSuboptimalKHR) {
            rebuild_needed_ = true;
            return false;
        }
        if (res == vk::Result::eSuboptimalKHR) rebuild_needed_ = true;   // draw this one, rebuild after presenting
        image = idx;
    } catch (const vk::OutOfDateKHRError&) {
        rebuild_needed_ = true;
        return false;
    }
    ctx_.device().resetFences(*s.fence);
    s.cb.reset();
    s.cb.begin({.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    vk::ClearValue clear{vk::ClearColorValue{std::array<float, 4>{0.10f, 0.10f, 0.11f, 1.0f}}};
    s.cb.beginRenderPass(vk::RenderPassBeginInfo{.renderPass = *render_pass_,
                                                 .framebuffer = *framebuffers_[image],
                                                 .renderArea = {{0, 0}, extent_},
                                                 .clearValueCount = 1,
                                                 .pClearValues = &clear},
                         vk::SubpassContents::eInline);
    f.cb = *s.cb;
    f.extent = extent_;
    f.slot = next_slot_;
    f.image = image;
    return true;
}

void Presenter::end(Frame& f, bool capture) {
    Slot& s = slots_[f.slot];
    s.cb.endRenderPass();
    capture = capture && can_capture_;
    if (capture) {
        const vk::DeviceSize bytes = vk::DeviceSize(extent_.width) * extent_.height * 4;
        if (!*capture_.buffer || capture_.size < bytes) {
            ctx_.device().waitIdle();
            capture_ = ctx_.make_buffer(bytes, vk::BufferUsageFlagBits::eTransferDst, false);
        }
        capture_extent_ = extent_;
        vk::ImageMemoryBarrier to_src{.srcAccessMask = vk::AccessFlagBits::eColorAttachmentWrite,
                                      .dstAccessMask = vk::AccessFlagBits::eTransferRead,
                                      .oldLayout = vk::ImageLayout::ePresentSrcKHR,
                                      .newLayout = vk::ImageLayout::eTransferSrcOptimal,
                                      .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .image = images_[f.image],
                                      .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}};
        s.cb.pipelineBarrier(vk::PipelineStageFlagBits::eColorAttachmentOutput, vk::PipelineStageFlagBits::eTransfer,
                             {}, nullptr, nullptr, to_src);
        vk::BufferImageCopy region{.bufferOffset = 0,
                                   .bufferRowLength = 0,
                                   .bufferImageHeight = 0,
                                   .imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                   .imageOffset = {0, 0, 0},
                                   .imageExtent = {extent_.width, extent_.height, 1}};
        s.cb.copyImageToBuffer(images_[f.image], vk::ImageLayout::eTransferSrcOptimal, *capture_.buffer, region);
        vk::ImageMemoryBarrier back{.srcAccessMask = vk::AccessFlagBits::eTransferRead,
                                    .dstAccessMask = {},
                                    .oldLayout = vk::ImageLayout::eTransferSrcOptimal,
                                    .newLayout = vk::ImageLayout::ePresentSrcKHR,
                                    .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                    .image = images_[f.image],
                                    .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1}};
        vk::BufferMemoryBarrier to_host{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                        .dstAccessMask = vk::AccessFlagBits::eHostRead,
                                        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                        .buffer = *capture_.buffer,
                                        .offset = 0,
                                        .size = VK_WHOLE_SIZE};
        s.cb.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                             vk::PipelineStageFlagBits::eBottomOfPipe | vk::PipelineStageFlagBits::eHost, {}, nullptr,
                             to_host, back);
    }
    s.cb.end();
    vk::PipelineStageFlags wait_stage = vk::PipelineStageFlagBits::eColorAttachmentOutput;
    vk::Semaphore acquired = *s.acquired, rendered = *rendered_[f.image];
    vk::CommandBuffer cb = *s.cb;
    ctx_.queue().submit(vk::SubmitInfo{.waitSemaphoreCount = 1,
                                       .pWaitSemaphores = &acquired,
                                       .pWaitDstStageMask = &wait_stage,
                                       .commandBufferCount = 1,
                                       .pCommandBuffers = &cb,
                                       .signalSemaphoreCount = 1,
                                       .pSignalSemaphores = &rendered},
                        *s.fence);
    vk::SwapchainKHR sc = *swapchain_;
    try {
        vk::Result r = ctx_.queue().presentKHR(vk::PresentInfoKHR{.waitSemaphoreCount = 1,
                                                                  .pWaitSemaphores = &rendered,
                                                                  .swapchainCount = 1,
                                                                  .pSwapchains = &sc,
                                                                  .pImageIndices = &f.image});
        if (r == vk::Result::eSuboptimalKHR) rebuild_needed_ = true;
    } catch (const vk::OutOfDateKHRError&) { rebuild_needed_ = true; }
    next_slot_ = (next_slot_ + 1) % kFramesInFlight;
    if (capture) {
        while (ctx_.device().waitForFences(*s.fence, VK_TRUE, 1000000000ull) == vk::Result::eTimeout) {}
        capture_ready_ = true;
    }
}

bool Presenter::take_capture(std::vector<uint8_t>& rgba, uint32_t& width, uint32_t& height) {
    if (!capture_ready_) return false;
    capture_ready_ = false;
    width = capture_extent_.width;
    height = capture_extent_.height;
    const uint8_t* p = static_cast<const uint8_t*>(capture_.mapped);
    rgba.resize(size_t(width) * height * 4);
    const bool bgra = format_ == vk::Format::eB8G8R8A8Unorm || format_ == vk::Format::eB8G8R8A8Srgb;
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        rgba[4 * i + 0] = p[4 * i + (bgra ? 2 : 0)];
        rgba[4 * i + 1] = p[4 * i + 1];
        rgba[4 * i + 2] = p[4 * i + (bgra ? 0 : 2)];
        rgba[4 * i + 3] = 255;
    }
    return true;
}

}   // namespace gonio::view
