// gonio-view: the interactive viewer. A window (GLFW + Vulkan swapchain on the CLI's device) with
// the progressive reference's hemisphere, the models and their differences, the in-plane slice and albedos,
// and controls for every parameter of the stack (Dear ImGui). Scripted runs (--frames, --set, --screenshot)
// need no human: tests/viewer_test.sh runs one under Xvfb.
#include "app.h"
#include "hemisphere.h"
#include "ui.h"
#include "vk_context.h"
#include "window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>
#include <stb_image_write.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

using namespace gonio;
using namespace gonio::view;

namespace {

const char* kHelp = R"(gonio-view: the interactive viewer of gonio (a virtual gonio-photometer for layered BRDFs)

usage: gonio-view STACK.toml [options]     (also: gonio view STACK.toml [options])

The window shows, for one incident angle, the reference's reflection hemisphere seen from above as it
accumulates (paths so far and the median relative standard error of the bins above 1% of the peak), beside
it the selected analytic models and their signed differences to the reference (model - reference after the
remap, on one symmetric scale), the in-plane slice (log(1 + sqrt f); reference dashed) and each one's
directional albedo. Controls: incident angle, channel (RGB, R, G, B, luminance), remap and exposure, the
models, and every parameter of the stack; a change re-evaluates the models and restarts the reference. The
stack file is watched: an edit is loaded at once; an invalid edit keeps the previous stack and shows why.
Save writes the stack (TOML), the hemispheres (EXR, the reference and the models, like gonio compare's) and
the window (PNG). Esc or Ctrl+Q closes the window.

options:
  --theta-i DEG        incident angle to start with (default 30)
  --phi-i DEG          incident azimuth to start with, in [0, 360) (default 0: the plane xz)
  --device N           Vulkan device, as `gonio devices` lists them (default: the CLI's choice)
  --validate           enable the Khronos validation layer; its messages are printed and counted
  --seed N             the reference's seed (default 1)
  --slice-ms MS        device time of the reference slice run each frame (default 10); smaller: more
                       frames per second, slower convergence
  --no-belcour-tables  Belcour's models without FGD/TIR tables (as gonio compare --no-belcour-tables)
  --size WxH           window size (default 1280x800)
  --model FILE         also show your own model, one GLSL file (repeatable; as gonio compare --model);
                       recompiled when the file changes (a broken edit keeps the previous model and says why)
  --help               this text

scripted runs (no human needed; used by the tests):
  --frames N           close after N frames and print frames per second
  --set KEY=VALUE      change a setting or a stack parameter at frame --set-frame, as the controls would
                       (repeatable). Keys:
@SETTINGS@  --set-frame N        frame at which --set applies (default 2)
  --screenshot FILE    write the last frame (of --frames) as PNG
  --resize F:WxH       resize the window at frame F (repeatable; 1x1 is allowed)
  --close-at N         ask the window to close at frame N, as the close button does
  --wait-paths N       before the screenshot, keep running until the reference has N paths (with --frames:
                       the frame count is then a minimum)

exit status: 0 on success; 1 on a runtime error; 2 on bad usage; 3 if the validation layer reported anything.
)";

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

[[noreturn]] void usage_error(const std::string& msg) {
    std::fprintf(stderr, "gonio-view: %s\n(run `gonio-view --help` for usage)\n", msg.c_str());
    std::exit(2);
}

long whole(const std::string& opt, const std::string& v, long lo, long hi) {
    char* end = nullptr;
    long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < lo || n > hi)
        usage_error(opt + ": expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                    "], got '" + v + "'");
    return n;
}

double real(const std::string& opt, const std::string& v) {
    char* end = nullptr;
    double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(d)) usage_error(opt + ": expected a number, got '" + v + "'");
    return d;
}

std::pair<int, int> size_of(const std::string& opt, const std::string& v) {
    auto x = v.find('x');
    if (x == std::string::npos) usage_error(opt + ": expected WxH, got '" + v + "'");
    return {int(whole(opt, v.substr(0, x), 1, 16384)), int(whole(opt, v.substr(x + 1), 1, 16384))};
}

struct Options {
    AppOptions app;
    int device = -1;
    bool validate = false;
    int width = 1280, height = 800;
    long frames = 0;
    std::vector<std::string> sets;
    long set_frame = 2;
    std::string screenshot;
    std::multimap<long, std::pair<int, int>> resizes;
    long close_at = -1;
    uint64_t wait_paths = 0;
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            std::string help = kHelp;
            help.replace(help.find("@SETTINGS@"), 10, settings_help());
            std::fputs(help.c_str(), stdout);
            std::exit(0);
        } else if (a == "--theta-i")
            o.app.theta_i_deg = real(a, value());
        else if (a == "--phi-i")
            o.app.phi_i_deg = real(a, value());
        else if (a == "--device")
            o.device = int(whole(a, value(), 0, 64));
        else if (a == "--validate")
            o.validate = true;
        else if (a == "--seed")
            o.app.seed = uint32_t(whole(a, value(), 0, 0x7fffffffL));
        else if (a == "--slice-ms") {
            o.app.slice_ms = real(a, value());
            if (!(o.app.slice_ms > 0 && o.app.slice_ms <= 1000)) usage_error("--slice-ms must be in (0, 1000]");
        } else if (a == "--no-belcour-tables")
            o.app.belcour_tables = false;
        else if (a == "--size")
            std::tie(o.width, o.height) = size_of(a, value());
        else if (a == "--model")
            o.app.model_files.push_back(value());
        else if (a == "--frames")
            o.frames = whole(a, value(), 1, 100000000);
        else if (a == "--set")
            o.sets.push_back(value());
        else if (a == "--set-frame")
            o.set_frame = whole(a, value(), 0, 100000000);
        else if (a == "--screenshot")
            o.screenshot = value();
        else if (a == "--resize") {
            std::string v = value();
            auto c = v.find(':');
            if (c == std::string::npos) usage_error("--resize: expected FRAME:WxH, got '" + v + "'");
            o.resizes.emplace(whole(a, v.substr(0, c), 0, 100000000), size_of(a, v.substr(c + 1)));
        } else if (a == "--close-at")
            o.close_at = whole(a, value(), 0, 100000000);
        else if (a == "--wait-paths")
            o.wait_paths = uint64_t(whole(a, value(), 0, 1L << 40));
        else if (a.rfind("--", 0) == 0)
            usage_error("unknown option " + a);
        else if (o.app.stack_path.empty())
            o.app.stack_path = a;
        else
            usage_error("one stack file, please (got '" + o.app.stack_path + "' and '" + a + "')");
    }
    if (o.app.stack_path.empty()) usage_error("no stack file (e.g. gonio-view stacks/frosted-metal.toml)");
    if (!std::filesystem::exists(o.app.stack_path)) usage_error(o.app.stack_path + ": no such file");
    if (!(o.app.theta_i_deg >= 0 && o.app.theta_i_deg < 90)) usage_error("--theta-i must be in [0, 90) degrees");
    if (!(o.app.phi_i_deg >= 0 && o.app.phi_i_deg < 360)) usage_error("--phi-i must be in [0, 360) degrees");
    if (!o.screenshot.empty() && o.frames == 0)
        usage_error("--screenshot needs --frames (the picture is of the last frame)");
    return o;
}

void check_vk(VkResult r) {
    if (r != VK_SUCCESS) std::fprintf(stderr, "gonio-view: Dear ImGui's Vulkan backend: VkResult %d\n", int(r));
}

void key_callback(GLFWwindow* w, int key, int scancode, int action, int mods) {
    ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
    if (action == GLFW_PRESS && (key == GLFW_KEY_ESCAPE || (key == GLFW_KEY_Q && (mods & GLFW_MOD_CONTROL))))
        glfwSetWindowShouldClose(w, GLFW_TRUE);
}

bool write_png(const std::string& path, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h) {
    std::filesystem::path p(path);
    std::error_code ec;
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
    return stbi_write_png(path.c_str(), int(w), int(h), 4, rgba.data(), int(w) * 4) != 0;
}

VkContext make_context(const Options& o) {
    ContextOptions co;
    co.device_index = o.device;
    co.validation = o.validate;
    co.instance_extensions = Window::instance_extensions();
    co.device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    co.queue_filter = &Window::can_present;
    return VkContext(co);
}

// Dear ImGui on the window (its input callbacks, beside the viewer's keys) and on the presenter's render pass, its
// fonts uploaded; the descriptor pool it draws from is returned (it must outlive stop_imgui).
vk::raii::DescriptorPool start_imgui(VkContext& ctx, Window& window, Presenter& presenter) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;   // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window.glfw(), false);
    glfwSetKeyCallback(window.glfw(), key_callback);
    glfwSetMouseButtonCallback(window.glfw(), ImGui_ImplGlfw_MouseButtonCallback);
    glfwSetScrollCallback(window.glfw(), ImGui_ImplGlfw_ScrollCallback);
    glfwSetCharCallback(window.glfw(), ImGui_ImplGlfw_CharCallback);
    glfwSetWindowFocusCallback(window.glfw(), ImGui_ImplGlfw_WindowFocusCallback);
    glfwSetCursorEnterCallback(window.glfw(), ImGui_ImplGlfw_CursorEnterCallback);
    vk::DescriptorPoolSize pool_size{.type = vk::DescriptorType::eCombinedImageSampler, .descriptorCount = 4};
    vk::raii::DescriptorPool imgui_pool(
        ctx.device(), vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                                   .maxSets = 4,
                                                   .poolSizeCount = 1,
                                                   .pPoolSizes = &pool_size});
    ImGui_ImplVulkan_InitInfo ii{};
    ii.Instance = *ctx.instance();
    ii.PhysicalDevice = *ctx.physical();
    ii.Device = *ctx.device();
    ii.QueueFamily = ctx.queue_family();
    ii.Queue = ctx.queue();
    ii.DescriptorPool = *imgui_pool;
    ii.MinImageCount = Presenter::kFramesInFlight;
    ii.ImageCount = Presenter::kFramesInFlight;
    ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    ii.CheckVkResultFn = check_vk;
    ImGui_ImplVulkan_Init(&ii, presenter.render_pass());
    ctx.run_now([&](vk::CommandBuffer c) { ImGui_ImplVulkan_CreateFontsTexture(c); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return imgui_pool;
}

// Dear ImGui's teardown, once the device is idle.
void stop_imgui(Presenter& presenter) {
    presenter.wait_idle();
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

// What the loop keeps between frames: the frame counts, the clocks, and host seconds per part of a frame.
struct LoopStats {
    long frame = 0, drawn = 0;
    std::chrono::steady_clock::time_point t_start = std::chrono::steady_clock::now(), t_last = t_start;
    double fps_avg = 0.0;
    std::vector<double> frame_times;
    double cost_tick = 0, cost_wait = 0, cost_ui = 0, cost_submit = 0;   // host seconds per part of a frame
};

// The viewer's parts, as the steps of its loop use them.
struct Viewer {
    const Options& o;
    Window& window;
    Presenter& presenter;
    App& app;
    ViewState& view;
    PanelColours& colours;
    HemisphereRenderer& hemi;
    LoopStats stats;
    int status = 0;
    bool shot_done;   // the --screenshot is written (or none was asked for)
};

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// What the scripted run asks of this frame: --resize, --close-at, and --set at --set-frame (a refused setting closes
// the window with status 2).
void apply_scripted_changes(Viewer& v) {
    const Options& o = v.o;
    const long frame = v.stats.frame;
    for (auto [it, end] = o.resizes.equal_range(frame); it != end; ++it) {
        std::fprintf(stderr, "gonio-view: frame %ld: resizing the window to %dx%d\n", frame, it->second.first,
                     it->second.second);
        v.window.set_size(it->second.first, it->second.second);
    }
    if (frame == o.close_at) v.window.request_close();
    if (frame == o.set_frame)
        for (const auto& s : o.sets) {
            try {
                apply_setting(v.app, v.view, s);
            } catch (const std::invalid_argument& e) {
                std::fprintf(stderr, "gonio-view: %s\n", e.what());
                v.status = 2;
                v.window.request_close();
            }
        }
}

// The panels of frame f drawn (Dear ImGui, the hemispheres) and presented, the swapchain image kept for a screenshot
// if one is due (the last scripted frame, or the Save PNG button). Whether it was kept.
bool draw_and_present(Viewer& v, Frame& f, bool last, std::chrono::steady_clock::time_point c2) {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_ui(v.app, v.view, v.colours, v.hemi, f.slot);
    ImGui::Render();
    auto c3 = std::chrono::steady_clock::now();
    v.stats.cost_ui += seconds_between(c2, c3);
    ImDrawData* dd = ImGui::GetDrawData();
    v.hemi.begin_render(f.cb, f.extent, f.slot, dd);
    ImGui_ImplVulkan_RenderDrawData(dd, f.cb);
    const bool capture = (last && !v.o.screenshot.empty()) || v.view.want_screenshot;
    v.presenter.end(f, capture);
    v.hemi.end_frame();
    v.stats.cost_submit += seconds_between(c3, std::chrono::steady_clock::now());
    return capture;
}

// The kept swapchain image written as PNG: to the Save button's path or to --screenshot; said in the window's notice.
void save_screenshot(Viewer& v) {
    std::vector<uint8_t> rgba;
    uint32_t w = 0, h = 0;
    const std::string path = v.view.want_screenshot ? v.view.screenshot_path : v.o.screenshot;
    if (v.presenter.take_capture(rgba, w, h) && write_png(path, rgba, w, h)) {
        v.app.set_notice("wrote " + path);
        std::fprintf(stderr, "gonio-view: wrote %s (%ux%u)\n", path.c_str(), w, h);
        if (!v.view.want_screenshot) v.shot_done = true;
    } else {
        v.app.set_notice("could not save " + path +
                         " (the swapchain cannot be read back, or the file cannot be written)");
        std::fprintf(stderr, "gonio-view: %s\n", v.app.notice().c_str());
    }
    v.view.want_screenshot = false;
}

// A drawn frame's time: the frame rate the panels show (a running average) and the frame times of the summary.
void count_drawn_frame(Viewer& v) {
    LoopStats& s = v.stats;
    auto now = std::chrono::steady_clock::now();
    double dt = seconds_between(s.t_last, now);
    s.t_last = now;
    if (s.drawn > 0) s.frame_times.push_back(dt);
    s.fps_avg = s.fps_avg == 0.0 ? 1.0 / std::max(dt, 1e-6) : 0.9 * s.fps_avg + 0.1 / std::max(dt, 1e-6);
    v.view.fps = s.fps_avg;
    v.view.frame_ms = dt * 1e3;
    ++s.drawn;
    ++s.frame;
}

// One frame: the scripted changes due, the reference's slice of work and bookkeeping, the panels drawn and
// presented, a screenshot if one is due. False when the loop ends (the last frame of --frames, with --wait-paths
// paths).
bool run_frame(Viewer& v) {
    const Options& o = v.o;
    LoopStats& s = v.stats;
    const bool last = o.frames > 0 && s.frame >= o.frames - 1 && v.app.display().paths >= o.wait_paths;
    glfwPollEvents();
    apply_scripted_changes(v);
    auto c0 = std::chrono::steady_clock::now();
    v.app.tick(ImGui::GetCurrentContext() && ImGui::IsAnyItemActive());
    auto c1 = std::chrono::steady_clock::now();
    Frame f;
    const bool began = v.presenter.begin(f);
    auto c2 = std::chrono::steady_clock::now();
    s.cost_tick += seconds_between(c0, c1);
    s.cost_wait += seconds_between(c1, c2);
    if (!began) {   // minimised or no pixels: wait a little, keep accumulating
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        ++s.frame;
        return !(o.frames > 0 && s.frame >= o.frames && v.app.display().paths >= o.wait_paths);
    }
    if (draw_and_present(v, f, last, c2)) save_screenshot(v);
    count_drawn_frame(v);
    return !last;
}

// The summary on stderr: frames per second and frame times, the reference's paths and error, host time per part of
// a frame.
void print_frame_summary(const Viewer& v) {
    const LoopStats& st = v.stats;
    const double total = seconds_between(st.t_start, std::chrono::steady_clock::now());
    if (st.frame_times.empty()) return;
    std::vector<double> s = st.frame_times;
    std::sort(s.begin(), s.end());
    double sum = 0;
    for (double t : s) sum += t;
    std::fprintf(
        stderr,
        "gonio-view: %ld frames drawn in %.2f s; %.1f frames/s (mean frame %.1f ms, median %.1f ms, 95th percentile %.1f ms); "
        "reference %llu paths, median rse %.3g; models evaluated in %.2f s\n",
        st.drawn, total, double(s.size()) / sum, 1e3 * sum / double(s.size()), 1e3 * s[s.size() / 2],
        1e3 * s[std::min(s.size() - 1, size_t(0.95 * double(s.size())))], (unsigned long long)v.app.display().paths,
        v.app.display().median_rse[v.view.side], v.app.model_seconds());
    std::fprintf(
        stderr,
        "gonio-view: per frame: reference bookkeeping %.1f ms, waiting for the device %.1f ms, panels %.1f ms, "
        "recording and presenting %.1f ms\n",
        1e3 * st.cost_tick / double(st.frame), 1e3 * st.cost_wait / double(st.frame),
        1e3 * st.cost_ui / double(st.drawn), 1e3 * st.cost_submit / double(st.drawn));
}

// The exit status after the loop (see --help), with where the panels were for a scripted run.
int exit_status(const Viewer& v, const VkContext& ctx) {
    const Options& o = v.o;
    int status = v.status;
    if (o.frames > 0)   // where the panels were (tests look at the screenshot there)
        for (const auto& [name, r] : v.view.panels)
            std::fprintf(stderr, "gonio-view: panel %s at %.0f %.0f size %.0f\n", name.c_str(), r[0], r[1], r[2]);
    if (!v.shot_done) {
        std::fprintf(stderr, "gonio-view: the screenshot %s was not written\n", o.screenshot.c_str());
        if (status == 0) status = 1;
    }
    if (o.validate && ctx.validation_messages() > 0) {
        std::fprintf(stderr, "gonio-view: the validation layer reported %llu messages\n",
                     (unsigned long long)ctx.validation_messages());
        status = 3;
    }
    return status;
}

int run(const Options& o) {
    VkContext ctx = make_context(o);
    Window window(o.width, o.height, "gonio view: " + o.app.stack_path);
    Presenter presenter(ctx, window);
    std::fprintf(stderr, "gonio-view: device %s (%s)\n", ctx.device_info().name.c_str(), ctx.driver_string().c_str());

    App app(ctx, o.app);
    ViewState view;
    PanelColours colours;
    select_default_models(view, app, 3);
    HemisphereRenderer hemi(ctx, presenter.render_pass(), Presenter::kFramesInFlight, app.display().n_theta,
                            app.display().n_phi, 1.0, 2.0);
    vk::raii::DescriptorPool imgui_pool = start_imgui(ctx, window, presenter);

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    Viewer v{o, window, presenter, app, view, colours, hemi, LoopStats{}, 0, o.screenshot.empty()};
    while (!window.should_close() && !g_stop && run_frame(v)) {}
    stop_imgui(presenter);
    print_frame_summary(v);
    return exit_status(v, ctx);
}

}   // namespace

int main(int argc, char** argv) {
    Options o = parse(argc, argv);
    try {
        return run(o);
    } catch (const StackError& e) {   // a refused input file (the stack, a --model file): FILE:LINE
        std::fprintf(stderr, "gonio-view: %s\n", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {   // a refused option or a --model file that does not compile
        std::fprintf(stderr, "gonio-view: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gonio-view: %s\n", e.what());
        return 1;
    }
}
