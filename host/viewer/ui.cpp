#include "ui.h"
#include "output.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace gonio::view {

namespace {

const ImU32 kModelColours[] = {IM_COL32(230, 85, 70, 255),   IM_COL32(250, 160, 40, 255), IM_COL32(235, 120, 200, 255),
                               IM_COL32(60, 200, 220, 255),  IM_COL32(90, 140, 250, 255), IM_COL32(90, 200, 100, 255),
                               IM_COL32(170, 120, 240, 255), IM_COL32(190, 140, 90, 255)};
const char* kChannels[] = {"RGB", "R", "G", "B", "luminance"};
const char* kKinds[] = {"dielectric", "conductor", "lambertian"};

ImU32 model_colour(size_t m) { return kModelColours[m % (sizeof(kModelColours) / sizeof(kModelColours[0]))]; }

float pick(const float* rgb, int channel) {
    if (channel >= 1 && channel <= 3) return rgb[channel - 1];
    return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

float shape(float f, bool remap) { return remap ? std::log1p(std::sqrt(std::max(f, 0.0f))) : f; }

void hemisphere_panel(ViewState& v, HemisphereRenderer& hemi, const HemisphereParams& p, float size, const char* label,
                      ImU32 label_colour) {
    ImGui::BeginGroup();
    ImGui::PushStyleColor(ImGuiCol_Text, label_colour);
    ImGui::TextUnformatted(label);
    ImGui::PopStyleColor();
    ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(size, size));
    if (size >= 4.0f) hemi.add(ImGui::GetWindowDrawList(), p0, ImVec2(p0.x + size, p0.y + size), p);
    std::string name = label;
    name = name.substr(0, name.find(':'));
    for (char& c : name)
        if (c == ' ') c = '_';
    v.panels.push_back({name, {p0.x, p0.y, size}});
    ImGui::EndGroup();
}

void dashed_polyline(ImDrawList* dl, const std::vector<ImVec2>& pts, ImU32 col, float thickness) {
    for (size_t i = 0; i + 1 < pts.size(); ++i)
        if ((i / 2) % 2 == 0) dl->AddLine(pts[i], pts[i + 1], col, thickness);
}

void slice_plot(const App& app, const ViewState& v, ImVec2 size) {
    const Display& d = app.display();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy(size);
    if (size.x < 60 || size.y < 40) return;
    const float left = 44, right = 8, top = 6, bottom = 22;
    ImVec2 a(p0.x + left, p0.y + top), b(p0.x + size.x - right, p0.y + size.y - bottom);
    dl->AddRectFilled(a, b, IM_COL32(28, 28, 32, 255));
    const int side = v.side;
    const uint32_t nt = d.n_theta, np = d.n_phi;
    const int channel = v.channel == 0 ? 4 : v.channel;   // curves: luminance in RGB mode
    auto curve = [&](const std::vector<float>& f) {
        std::vector<std::pair<float, float>> pts;   // (theta_o signed, value)
        if (f.size() != d.bin_floats) return pts;
        for (int t = int(nt) - 1; t >= 0; --t)
            pts.push_back({-(t + 0.5f) * 90.0f / nt, shape(pick(&f[(size_t(t) * np + 0) * 3], channel), v.remap)});
        for (uint32_t t = 0; t < nt; ++t)
            pts.push_back({(t + 0.5f) * 90.0f / nt, shape(pick(&f[(size_t(t) * np + np / 2) * 3], channel), v.remap)});
        return pts;
    };
    std::vector<std::pair<std::vector<std::pair<float, float>>, size_t>> curves;   // (points, source)
    curves.push_back({curve(d.values[side]), 0});
    for (size_t m = 0; m < v.show.size(); ++m)
        if (v.show[m]) curves.push_back({curve(d.values[2 * (1 + m) + side]), 1 + m});
    float ymax = 0;
    for (auto& [pts, s] : curves)
        for (auto& [x, y] : pts) ymax = std::max(ymax, y);
    ymax = ymax > 0 ? ymax * 1.05f : 1.0f;
    auto X = [&](float th) { return a.x + (th + 90.0f) / 180.0f * (b.x - a.x); };
    auto Y = [&](float y) { return b.y - std::clamp(y / ymax, 0.0f, 1.0f) * (b.y - a.y); };
    for (int th = -90; th <= 90; th += 30) {
        dl->AddLine(ImVec2(X(th), a.y), ImVec2(X(th), b.y), IM_COL32(60, 60, 66, 255));
        char buf[16];
        std::snprintf(buf, sizeof buf, "%d", th);
        dl->AddText(ImVec2(X(th) - 8, b.y + 3), IM_COL32(180, 180, 180, 255), buf);
    }
    for (int k = 0; k <= 4; ++k) {
        float y = ymax * k / 4.0f;
        dl->AddLine(ImVec2(a.x, Y(y)), ImVec2(b.x, Y(y)), IM_COL32(60, 60, 66, 255));
        char buf[16];
        std::snprintf(buf, sizeof buf, "%.2g", y);
        dl->AddText(ImVec2(p0.x + 2, Y(y) - 7), IM_COL32(180, 180, 180, 255), buf);
    }
    if (side == 0)
        dl->AddLine(ImVec2(X(float(app.theta_i())), a.y), ImVec2(X(float(app.theta_i())), b.y),
                    IM_COL32(230, 190, 30, 255), 1.5f);
    dl->PushClipRect(a, b, true);
    for (size_t i = curves.size(); i-- > 0;) {
        auto& [pts, s] = curves[i];
        std::vector<ImVec2> screen;
        for (auto& [x, y] : pts) screen.push_back(ImVec2(X(x), Y(y)));
        if (screen.size() < 2) continue;
        if (s == 0)
            dashed_polyline(dl, screen, IM_COL32(250, 250, 250, 255), 2.0f);
        else
            dl->AddPolyline(screen.data(), int(screen.size()), model_colour(s - 1), 0, 1.6f);
    }
    dl->PopClipRect();
}

bool drag3(const char* label, glm::vec3& v, float speed, float lo, float hi, const char* fmt = "%.3f") {
    return ImGui::DragFloat3(label, &v.x, speed, lo, hi, fmt, ImGuiSliderFlags_AlwaysClamp);
}

void stack_controls(App& app) {
    Stack& e = app.edit();
    bool changed = false;
    changed |=
        ImGui::DragFloat("exterior IOR", &e.exterior_ior, 0.005f, 1.0f, 4.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
    for (size_t i = 0; i < e.layers.size(); ++i) {
        Layer& L = e.layers[i];
        ImGui::PushID(int(i));
        char title[96];
        std::snprintf(title, sizeof title, "layer %zu: %s%s###layer", i + 1, kKinds[int(L.kind)],
                      i == 0 ? " (top)" : (i + 1 == e.layers.size() ? " (base)" : ""));
        if (ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen)) {
            int kind = int(L.kind);
            if (ImGui::Combo("interface", &kind, kKinds, 3)) {
                L.kind = InterfaceKind(kind);
                changed = true;
            }
            if (L.kind != InterfaceKind::Lambertian)
                changed |=
                    ImGui::SliderFloat("roughness", &L.roughness, 0.0f, 1.0f, "%.4f", ImGuiSliderFlags_Logarithmic);
            if (L.kind == InterfaceKind::Dielectric) {
                changed |= drag3("ior", L.ior, 0.005f, 1.0f, 4.0f);
                changed |= drag3("optical depth", L.optical_depth, 0.01f, 0.0f, 50.0f);
                if (i + 1 < e.layers.size()) {   // the substrate under a transmissive stack has no medium
                    changed |= drag3("scattering albedo", L.scattering_albedo, 0.005f, 0.0f, 1.0f);
                    changed |= ImGui::SliderFloat("phase g", &L.phase_g, -0.99f, 0.99f, "%.3f");
                }
            } else if (L.kind == InterfaceKind::Conductor) {
                changed |= drag3("ior (n)", L.ior, 0.01f, 0.01f, 10.0f);
                changed |= drag3("k", L.k, 0.01f, 0.0f, 20.0f);
            } else {
                changed |= ImGui::ColorEdit3("albedo", &L.albedo.x, ImGuiColorEditFlags_Float);
            }
        }
        ImGui::PopID();
    }
    if (changed) app.set_stack(e, "controls");
}

std::string base_name(const App& app) {
    return app.stack().name.empty() ? std::string("stack") : safe_file_name(app.stack().name);
}

void save_controls(App& app, ViewState& v) {
    ImGui::InputText("folder", &v.save_dir);
    const std::string stem = (std::filesystem::path(v.save_dir) / (base_name(app) + "-view")).string();
    try {
        if (ImGui::Button("stack .toml")) app.set_notice("wrote " + app.save_stack(stem + ".toml"));
        ImGui::SameLine();
        if (ImGui::Button("hemispheres .exr")) app.set_notice("wrote " + app.save_exr(stem + ".exr"));
        ImGui::SameLine();
        if (ImGui::Button("window .png")) {
            v.want_screenshot = true;
            v.screenshot_path = stem + ".png";
        }
    } catch (const std::exception& e) { app.set_notice(std::string("save failed: ") + e.what()); }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("files are named after the stack: %s-view.*", base_name(app).c_str());
}

void controls(App& app, ViewState& v) {
    const Display& d = app.display();
    ImGui::TextWrapped("%s", app.stack_path().c_str());
    ImGui::TextDisabled("%s", app.stack().description.c_str());
    if (!app.error().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 110, 100, 255));
        ImGui::TextWrapped("%s", app.error().c_str());
        ImGui::PopStyleColor();
    }
    ImGui::Separator();
    float ti = float(app.theta_i());
    if (ImGui::SliderFloat("theta_i (deg)", &ti, 0.0f, 89.0f, "%.1f")) app.set_theta_i(ti);
    ImGui::Combo("channel", &v.channel, kChannels, 5);
    ImGui::Checkbox("log(1 + sqrt f)", &v.remap);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-90);
    ImGui::SliderFloat("exposure", &v.exposure, -6.0f, 6.0f, "%+.1f stops");
    if (app.transmissive()) {
        ImGui::RadioButton("reflection", &v.side, 0);
        ImGui::SameLine();
        ImGui::RadioButton("transmission", &v.side, 1);
    } else {
        v.side = 0;
    }
    if (ImGui::CollapsingHeader("models", ImGuiTreeNodeFlags_DefaultOpen)) {
        v.show.resize(app.model_count(), false);
        for (size_t m = 0; m < app.model_count(); ++m) {
            std::string why = app.model_cannot_represent_here(m);
            ImGui::BeginDisabled(!why.empty());
            ImGui::PushStyleColor(ImGuiCol_CheckMark, model_colour(m));
            bool on = v.show[m] && why.empty();
            if (ImGui::Checkbox(app.model_id(m).c_str(), &on)) v.show[m] = on;
            ImGui::PopStyleColor();
            ImGui::EndDisabled();
            if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
                ImGui::SetTooltip("%s%s%s", app.model_description(m).c_str(),
                                  why.empty() ? "" : "\ncannot represent this stack: ", why.c_str());
            if (m % 2 == 0 && m + 1 < app.model_count()) ImGui::SameLine(ImGui::GetContentRegionAvail().x * 0.5f);
        }
        ImGui::TextDisabled("models evaluated in %.2f s", app.model_seconds());
    }
    if (ImGui::CollapsingHeader("stack", ImGuiTreeNodeFlags_DefaultOpen)) stack_controls(app);
    if (ImGui::CollapsingHeader("save", ImGuiTreeNodeFlags_DefaultOpen)) save_controls(app, v);
    if (!app.notice().empty()) ImGui::TextWrapped("%s", app.notice().c_str());
    ImGui::Separator();
    ImGui::Text("%.1f frames/s (%.1f ms)", v.fps, v.frame_ms);
    ImGui::Text("reference %.2f Mpaths/s", d.mpaths_per_s);
}

}   // namespace

void select_default_models(ViewState& v, const App& app, size_t count) {
    // one of each family first (Weidlich-Wilkie corrected, Belcour 2018, transfer matrices), then the rest
    v.show.assign(app.model_count(), false);
    std::vector<size_t> order;
    // the users' models first: they are why --model was given
    for (size_t m = model_registry().size(); m < app.model_count(); ++m) order.push_back(m);
    for (const char* id : {"ww-corrected", "belcour18-forward", "tm21"})
        for (size_t m = 0; m < app.model_count(); ++m)
            if (app.model_id(m) == id) order.push_back(m);
    for (size_t m = 0; m < app.model_count(); ++m)
        if (std::find(order.begin(), order.end(), m) == order.end()) order.push_back(m);
    size_t n = 0;
    for (size_t m : order)
        if (n < count && app.model_cannot_represent_here(m).empty()) {
            v.show[m] = true;
            ++n;
        }
}

std::string settings_help() {
    return "  theta_i=DEG  channel=rgb|r|g|b|lum  remap=0|1  exposure=STOPS  side=r|t  models=ID,ID|all|none\n"
           "  exterior_ior=X  layer.N.interface=dielectric|conductor|lambertian  layer.N.roughness=X\n"
           "  layer.N.ior=X[,Y,Z]  layer.N.k=X[,Y,Z]  layer.N.optical_depth=X[,Y,Z]  layer.N.albedo=X[,Y,Z]\n"
           "  layer.N.scattering_albedo=X[,Y,Z]  layer.N.phase_g=X\n"
           "  (layers are numbered from 1, top first)  save_dir=DIR  save=toml|exr|png (as the save buttons)\n";
}

void apply_setting(App& app, ViewState& v, const std::string& kv) {
    auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--set " + kv + ": expected key=value");
    const std::string key = kv.substr(0, eq), val = kv.substr(eq + 1);
    auto bad = [&](const std::string& why) { return std::invalid_argument("--set " + kv + ": " + why); };
    auto number = [&](const std::string& s) {
        char* end = nullptr;
        double d = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !std::isfinite(d)) throw bad("expected a number, got '" + s + "'");
        return d;
    };
    auto vec3 = [&]() {
        std::vector<double> xs;
        std::stringstream ss(val);
        std::string part;
        while (std::getline(ss, part, ',')) xs.push_back(number(part));
        if (xs.size() == 1) return glm::vec3(float(xs[0]));
        if (xs.size() == 3) return glm::vec3(float(xs[0]), float(xs[1]), float(xs[2]));
        throw bad("expected one number or three (R,G,B)");
    };
    if (key == "theta_i") {
        app.set_theta_i(number(val));
        return;
    }
    if (key == "channel") {
        const char* names[] = {"rgb", "r", "g", "b", "lum"};
        for (int i = 0; i < 5; ++i)
            if (val == names[i]) {
                v.channel = i;
                return;
            }
        throw bad("channel is rgb, r, g, b or lum");
    }
    if (key == "remap") {
        v.remap = number(val) != 0;
        return;
    }
    if (key == "exposure") {
        v.exposure = float(number(val));
        return;
    }
    if (key == "side") {
        if (val == "r")
            v.side = 0;
        else if (val == "t" && app.transmissive())
            v.side = 1;
        else
            throw bad("side is r, or t for a transmissive stack");
        return;
    }
    if (key == "save_dir") {
        v.save_dir = val;
        return;
    }
    if (key == "save") {   // as the save buttons
        const std::string stem = (std::filesystem::path(v.save_dir) / (base_name(app) + "-view")).string();
        try {
            if (val == "toml")
                app.set_notice("wrote " + app.save_stack(stem + ".toml"));
            else if (val == "exr")
                app.set_notice("wrote " + app.save_exr(stem + ".exr"));
            else if (val == "png") {
                v.want_screenshot = true;
                v.screenshot_path = stem + ".png";
                return;
            } else
                throw bad("save is toml, exr or png");
        } catch (const std::invalid_argument&) { throw; } catch (const std::exception& e) {
            throw bad(e.what());
        }
        std::fprintf(stderr, "gonio-view: %s\n", app.notice().c_str());
        return;
    }
    if (key == "models") {
        v.show.assign(app.model_count(), val == "all");
        if (val == "all" || val == "none") return;
        std::stringstream ss(val);
        std::string id;
        while (std::getline(ss, id, ',')) {
            size_t m = 0;
            while (m < app.model_count() && app.model_id(m) != id) ++m;
            if (m == app.model_count()) throw bad("no model '" + id + "' (see `gonio models`, or --model files)");
            v.show[m] = true;
        }
        return;
    }
    Stack s = app.stack();
    if (key == "exterior_ior") {
        s.exterior_ior = float(number(val));
    } else if (key.rfind("layer.", 0) == 0) {
        auto dot = key.find('.', 6);
        if (dot == std::string::npos) throw bad("expected layer.N.parameter");
        double n = number(key.substr(6, dot - 6));
        if (n < 1 || n > double(s.layers.size()) || n != std::floor(n))
            throw bad("the stack has layers 1 to " + std::to_string(s.layers.size()));
        Layer& L = s.layers[size_t(n) - 1];
        const std::string p = key.substr(dot + 1);
        if (p == "roughness")
            L.roughness = float(number(val));
        else if (p == "ior")
            L.ior = vec3();
        else if (p == "k")
            L.k = vec3();
        else if (p == "optical_depth")
            L.optical_depth = vec3();
        else if (p == "albedo")
            L.albedo = vec3();
        else if (p == "scattering_albedo")
            L.scattering_albedo = vec3();
        else if (p == "phase_g")
            L.phase_g = float(number(val));
        else if (p == "interface") {
            int k = -1;
            for (int i = 0; i < 3; ++i)
                if (val == kKinds[i]) k = i;
            if (k < 0) throw bad("interface is dielectric, conductor or lambertian");
            L.kind = InterfaceKind(k);
        } else {
            throw bad("unknown layer parameter '" + p + "'");
        }
    } else {
        throw bad("unknown key; keys:\n" + settings_help());
    }
    app.set_stack(s, "--set " + kv);   // an invalid value keeps the previous stack and shows why
}

void draw_ui(App& app, ViewState& v, PanelColours& colours, HemisphereRenderer& hemi, uint32_t slot) {
    const Display& d = app.display();
    v.show.resize(app.model_count(), false);
    const int side = v.side;
    std::vector<size_t> shown;
    for (size_t m = 0; m < v.show.size(); ++m)
        if (v.show[m] && m < app.models().size() && model_has_bins(app.models()[m]) &&
            d.values[2 * (1 + m) + side].size() == d.bin_floats)
            shown.push_back(m);
    colours.update(d, ColourSettings{v.channel, v.remap, v.exposure, side, shown});
    hemi.upload(slot, colours.rgba(), colours.version());
    v.panels.clear();
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(io.DisplaySize);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
    ImGui::Begin("gonio view", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus);
    ImGui::PopStyleVar();
    ImGui::BeginChild("controls", ImVec2(std::min(360.0f, std::max(io.DisplaySize.x * 0.3f, 1.0f)), 0), true);
    controls(app, v);
    ImGui::EndChild();
    ImGui::SameLine();
    ImGui::BeginChild("views", ImVec2(0, 0), false);
    // the panels use the colours' model list (it may lag the checkboxes by a frame)
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float gap = ImGui::GetStyle().ItemSpacing.x, line = ImGui::GetTextLineHeightWithSpacing();
    const size_t cols = 1 + shown.size();
    float size = std::min((avail.x - gap * float(cols - 1)) / float(cols), (avail.y * 0.62f - 2 * line) / 2.0f);
    size = std::max(size, 0.0f);
    const float light = side == 0 ? float(std::sin(app.theta_i() * M_PI / 180.0)) : -1.0f;
    ImGui::BeginGroup();
    hemisphere_panel(v, hemi, HemisphereParams{colours.reference(), light}, size, "reference",
                     IM_COL32(240, 240, 240, 255));
    // the legend, wrapped to the panel's width so that every column is as wide as its panel
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + std::max(size, 1.0f));
    ImGui::TextWrapped("%.3g M paths, median relative standard error %.2g%% (bins above 1%% of the peak)",
                       double(d.paths) * 1e-6, d.median_rse[side] * 100.0);
    ImGui::TextWrapped("%s, %s, %s.%s", side == 0 ? "BRDF seen from above" : "BTDF seen from above",
                       kChannels[v.channel], v.remap ? "log(1 + sqrt f)" : "f",
                       side == 0 ? " The yellow dot is the light." : "");
    ImGui::TextWrapped("Below each model: model - reference, full colour at +-%.3g (red: model above, blue: below).",
                       double(colours.difference_scale()));
    ImGui::PopTextWrapPos();
    ImGui::EndGroup();
    for (size_t i = 0; i < shown.size(); ++i) {
        const size_t m = shown[i];
        ImGui::SameLine();
        ImGui::BeginGroup();
        const auto& id = app.model_id(m);
        hemisphere_panel(v, hemi, HemisphereParams{colours.model(i), light}, size, id.c_str(), model_colour(m));
        std::string dl = id + " - reference";
        hemisphere_panel(v, hemi, HemisphereParams{colours.difference(i), light}, size, dl.c_str(), model_colour(m));
        ImGui::EndGroup();
    }
    // the slice plot and the albedos
    const ImVec2 rest = ImGui::GetContentRegionAvail();
    const float table_w = std::min(300.0f, rest.x * 0.35f);
    ImGui::BeginGroup();
    ImGui::Text("in-plane slice (%s, theta_o < 0: the light's side), reference dashed",
                v.channel == 0 ? "luminance" : kChannels[v.channel]);
    slice_plot(app, v, ImVec2(std::max(rest.x - table_w - gap, 0.0f), std::max(rest.y - line, 0.0f)));
    ImGui::EndGroup();
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::Text("directional %s", side == 0 ? "albedo" : "transmittance");
    if (table_w > 40 &&
        ImGui::BeginTable("albedo", 4, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_RowBg, ImVec2(table_w, 0))) {
        ImGui::TableSetupColumn("source");
        ImGui::TableSetupColumn("R");
        ImGui::TableSetupColumn("G");
        ImGui::TableSetupColumn("B");
        ImGui::TableHeadersRow();
        auto row = [&](const char* name, ImU32 col, const glm::dvec3& a) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::PushStyleColor(ImGuiCol_Text, col);
            ImGui::TextUnformatted(name);
            ImGui::PopStyleColor();
            for (int c = 0; c < 3; ++c) {
                ImGui::TableNextColumn();
                ImGui::Text("%.4f", a[c]);
            }
        };
        row("reference", IM_COL32(240, 240, 240, 255), d.albedo[side]);
        for (size_t m : shown) row(app.model_id(m).c_str(), model_colour(m), d.albedo[2 * (1 + m) + side]);
        ImGui::EndTable();
    }
    ImGui::EndGroup();
    ImGui::EndChild();
    ImGui::End();
}

}   // namespace gonio::view
