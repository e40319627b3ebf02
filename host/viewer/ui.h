// ui.h: the viewer's panels (Dear ImGui): controls and stack parameters, hemisphere top views of the reference,
// the selected models and their differences, the in-plane slice plot, albedos, saving.
#pragma once
#include "app.h"
#include "colours.h"
#include "hemisphere.h"

#include <array>
#include <string>
#include <vector>

namespace gonio::view {

// How the panels show things (the controls that are not the stack).
struct ViewState {
    int channel = 0;   // 0 RGB, 1 R, 2 G, 3 B, 4 luminance
    bool remap = true;   // log(1 + sqrt f)
    float exposure = 0.0f;   // stops
    int side = 0;   // 0 reflection, 1 transmission
    std::vector<bool> show;   // per model of the registry
    std::vector<bool> listed;   // `show` when the model list last opened the families of the models shown
    std::string save_dir = ".";   // where Save writes
    bool want_screenshot = false;   // set by the Save PNG button; main takes the picture
    std::string screenshot_path;
    double fps = 0.0, frame_ms = 0.0;
    std::vector<std::pair<std::string, std::array<float, 3>>> panels;   // last frame's hemisphere panels: x, y, size
};

// Default model selection: the first `count` models that can represent the stack.
void select_default_models(ViewState& v, const App& app, size_t count);

// Applies one `key=value` setting (the --set option, as if by the controls). Throws std::invalid_argument
// with the list of keys when the key or value is not understood.
void apply_setting(App& app, ViewState& v, const std::string& key_value);
std::string settings_help();

// Builds this frame's panels. The panels' colours go to the renderer's buffer for the frame slot.
void draw_ui(App& app, ViewState& v, PanelColours& colours, HemisphereRenderer& hemi, uint32_t slot);

}   // namespace gonio::view
