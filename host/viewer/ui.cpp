#include "ui.h"
#include "output.h"
#include "stack_vocabulary.h"

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
const char* kChannelNames[] = {"RGB", "R", "G", "B", "luminance"};

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
    // the plane of incidence: the columns at the light's azimuth and opposite it (the nearest bins' columns)
    const uint32_t light_col = uint32_t(std::lround(app.phi_i() / 360.0 * np)) % np,
                   far_col = (light_col + np / 2) % np;
    auto curve = [&](const std::vector<float>& f) {
        std::vector<std::pair<float, float>> pts;   // (theta_o signed, value)
        if (f.size() != d.bin_floats) return pts;
        for (int t = int(nt) - 1; t >= 0; --t)
            pts.push_back(
                {-(t + 0.5f) * 90.0f / nt, shape(pick(&f[(size_t(t) * np + light_col) * 3], channel), v.remap)});
        for (uint32_t t = 0; t < nt; ++t)
            pts.push_back({(t + 0.5f) * 90.0f / nt, shape(pick(&f[(size_t(t) * np + far_col) * 3], channel), v.remap)});
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

// A medium's phase function, a choice of its words (stack_vocabulary.cpp `phase`): a medium turned into microflakes
// starts at alpha 0.5 and drops its Henyey-Greenstein g, one turned back drops its alpha (what the stack rules ask).
bool phase_control(Layer& L) {
    const ChoiceKey& c = *find_choice_key("phase");
    int word = c.get(L);
    auto word_of = [](void* d, int n, const char** out) {
        *out = static_cast<const ChoiceKey*>(d)->words[size_t(n)];
        return true;
    };
    if (!ImGui::Combo(c.name, &word, word_of, const_cast<ChoiceKey*>(&c), c.word_count())) return false;
    c.set(L, word);
    if (L.phase == MediumPhase::Hg) {
        L.fibre_roughness = 0.0f;
    } else {
        if (L.fibre_roughness == 0.0f) L.fibre_roughness = 0.5f;
        L.phase_g = 0.0f;
    }
    return true;
}

// One control per key of the layer's kind (stack_vocabulary.h), over the key's typical span: a roughness on a
// logarithmic slider down to 0, an albedo as a colour, the other RGB keys dragged per channel.
bool key_control(const LayerKey& key, Layer& L) {
    const ParameterRange r = key.typical.hi > key.typical.lo ? key.typical : key.range;
    const float lo = key.or_zero ? 0.0f : r.lo;
    if (key.number)
        return ImGui::SliderFloat(key.name, &(L.*key.number), lo, r.hi, key.or_zero ? "%.4f" : "%.3f",
                                  key.or_zero ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None);
    if (!key.medium && r.lo == 0.0f && r.hi == 1.0f)
        return ImGui::ColorEdit3(key.name, &(L.*key.rgb).x, ImGuiColorEditFlags_Float);
    return drag3(key.name, L.*key.rgb, (r.hi - lo) / 1000.0f, lo, r.hi);
}

void stack_controls(App& app) {
    Stack& e = app.edit();
    bool changed = false;
    for (const StackKey& k : stack_keys())
        changed |= ImGui::DragFloat(k.name, &(e.*k.value), 0.005f, k.range.lo, std::min(k.range.hi, 4.0f), "%.3f",
                                    ImGuiSliderFlags_AlwaysClamp);
    const auto kinds = interface_kinds();
    for (size_t i = 0; i < e.layers.size(); ++i) {
        Layer& L = e.layers[i];
        const bool substrate = i + 1 == e.layers.size();   // the substrate under a transmissive stack has no medium
        ImGui::PushID(int(i));
        char title[96];
        std::snprintf(title, sizeof title, "layer %zu: %s%s###layer", i + 1, to_string(L.kind),
                      i == 0 ? " (top)" : (substrate ? " (base)" : ""));
        if (ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen)) {
            int kind = int(&kind_info(L.kind) - kinds.data());
            auto name_of = [](void* d, int n, const char** out) {
                *out = static_cast<const KindInfo*>(d)[n].name;
                return true;
            };
            if (ImGui::Combo("interface", &kind, name_of, const_cast<KindInfo*>(kinds.data()), int(kinds.size()))) {
                L.kind = kinds[size_t(kind)].kind;
                changed = true;
            }
            if (L.kind == InterfaceKind::Dielectric && !substrate) changed |= phase_control(L);
            for (const LayerKey* key : keys_of(L.kind))
                if (!(key->medium && substrate) && key_of_layer_phase(*key, L)) changed |= key_control(*key, L);
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

// One model's checkbox on a line of its own (ids are long: a variant's is its model's with its suffixes), its colour as the mark,
// greyed where it cannot represent the stack, its citation in the tooltip.
void model_checkbox(const App& app, ViewState& v, size_t m) {
    const std::string why = app.model_cannot_represent_here(m);
    ImGui::BeginDisabled(!why.empty());
    ImGui::PushStyleColor(ImGuiCol_CheckMark, model_colour(m));
    bool on = v.show[m] && why.empty();
    if (ImGui::Checkbox(app.model_id(m).c_str(), &on)) v.show[m] = on;
    ImGui::PopStyleColor();
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s%s%s", app.model_description(m).c_str(),
                          why.empty() ? "" : "\ncannot represent this stack: ", why.c_str());
}

// The models by family (their headers' `family:`, then the users' files), one per line; each family a tree node,
// opened where a new selection shows a model (closed at first otherwise), its convention variants (ids with a '+') in a node of their own below the models
// as published: thirty models stay a short list.
void model_list(const App& app, ViewState& v) {
    std::vector<std::string> families;
    for (size_t m = 0; m < app.model_count(); ++m)
        if (std::find(families.begin(), families.end(), app.model_family(m)) == families.end())
            families.push_back(app.model_family(m));
    const bool reopen = v.listed != v.show;   // a new selection (the start, --set models=...): show where it is
    v.listed = v.show;
    for (const std::string& family : families) {
        std::vector<size_t> published, variants;
        size_t shown = 0;
        for (size_t m = 0; m < app.model_count(); ++m) {
            if (app.model_family(m) != family) continue;
            const bool variant = m < model_registry().size() && model_registry()[m].convention != 0;
            (variant ? variants : published).push_back(m);
            shown += v.show[m] ? 1 : 0;
        }
        const std::string label = family + " (" + std::to_string(published.size() + variants.size()) + ")###" + family;
        if (shown > 0 && reopen) ImGui::SetNextItemOpen(true);
        if (!ImGui::TreeNode(label.c_str())) continue;
        for (size_t m : published) model_checkbox(app, v, m);
        if (!variants.empty()) {
            const std::string vlabel = "variants (" + std::to_string(variants.size()) + ")###variants-" + family;
            if (reopen && std::any_of(variants.begin(), variants.end(), [&](size_t m) { return bool(v.show[m]); }))
                ImGui::SetNextItemOpen(true);
            if (ImGui::TreeNode(vlabel.c_str())) {
                for (size_t m : variants) model_checkbox(app, v, m);
                ImGui::TreePop();
            }
        }
        ImGui::TreePop();
    }
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
    float pi = float(app.phi_i());
    if (ImGui::SliderFloat("phi_i (deg)", &pi, 0.0f, 359.0f, "%.1f")) app.set_phi_i(pi);
    ImGui::Combo("channel", &v.channel, kChannelNames, 5);
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
        model_list(app, v);
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
    // the users' models first (they are why --model was given), then the first model of each family (its file's
    // `family:`, in the registry's order), then the rest
    v.show.assign(app.model_count(), false);
    std::vector<size_t> order;
    for (size_t m = model_registry().size(); m < app.model_count(); ++m) order.push_back(m);
    std::vector<std::string> families;
    for (size_t m = 0; m < model_registry().size() && m < app.model_count(); ++m) {
        const std::string& family = model_registry()[m].header.family;
        if (std::find(families.begin(), families.end(), family) != families.end()) continue;
        families.push_back(family);
        order.push_back(m);
    }
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
    std::string stack = "  ", layers = "  layer.N.interface=";
    for (const StackKey& k : stack_keys()) stack += std::string(k.name) + "=X  ";
    for (const KindInfo& k : interface_kinds())
        layers += std::string(k.name) + (&k == &interface_kinds().back() ? "" : "|");
    for (const std::string& name : layer_key_names()) layers += "  layer.N." + name + "=X[,Y,Z]";
    return "  theta_i=DEG  phi_i=DEG  channel=rgb|r|g|b|lum  remap=0|1  exposure=STOPS  side=r|t  models=ID,ID|all|none\n" +
           stack + "\n" + layers +
           "\n  (layers are numbered from 1, top first; a key of the layer's kind, as in a stack file)  save_dir=DIR  "
           "save=toml|exr|png (as the save buttons)\n";
}

namespace {

// One --set KEY=VALUE: its parts, its values parsed, and its refusals (std::invalid_argument naming it).
struct Setting {
    std::string kv, key, val;

    std::invalid_argument bad(const std::string& why) const {
        return std::invalid_argument("--set " + kv + ": " + why);
    }
    double number(const std::string& s) const {
        char* end = nullptr;
        double d = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !std::isfinite(d)) throw bad("expected a number, got '" + s + "'");
        return d;
    }
    double number() const { return number(val); }
    glm::vec3 rgb() const {
        std::vector<double> xs;
        std::stringstream ss(val);
        std::string part;
        while (std::getline(ss, part, ',')) xs.push_back(number(part));
        if (xs.size() == 1) return glm::vec3(float(xs[0]));
        if (xs.size() == 3) return glm::vec3(float(xs[0]), float(xs[1]), float(xs[2]));
        throw bad("expected one number or three (R,G,B)");
    }
};

// theta_i, phi_i, channel, remap, exposure, side, save_dir: true where the key is one of them
bool view_setting(App& app, ViewState& v, const Setting& s) {
    if (s.key == "theta_i") {
        app.set_theta_i(s.number());
    } else if (s.key == "phi_i") {
        app.set_phi_i(s.number());
    } else if (s.key == "channel") {
        const char* names[] = {"rgb", "r", "g", "b", "lum"};
        auto it = std::find_if(std::begin(names), std::end(names), [&](const char* n) { return s.val == n; });
        if (it == std::end(names)) throw s.bad("channel is rgb, r, g, b or lum");
        v.channel = int(it - std::begin(names));
    } else if (s.key == "remap") {
        v.remap = s.number() != 0;
    } else if (s.key == "exposure") {
        v.exposure = float(s.number());
    } else if (s.key == "side") {
        if (s.val == "r")
            v.side = 0;
        else if (s.val == "t" && app.transmissive())
            v.side = 1;
        else
            throw s.bad("side is r, or t for a transmissive stack");
    } else if (s.key == "save_dir") {
        v.save_dir = s.val;
    } else {
        return false;
    }
    return true;
}

// save=toml|exr|png, as the save buttons
void save_setting(App& app, ViewState& v, const Setting& s) {
    const std::string stem = (std::filesystem::path(v.save_dir) / (base_name(app) + "-view")).string();
    try {
        if (s.val == "toml")
            app.set_notice("wrote " + app.save_stack(stem + ".toml"));
        else if (s.val == "exr")
            app.set_notice("wrote " + app.save_exr(stem + ".exr"));
        else if (s.val == "png") {
            v.want_screenshot = true;
            v.screenshot_path = stem + ".png";
            return;
        } else
            throw s.bad("save is toml, exr or png");
    } catch (const std::invalid_argument&) { throw; } catch (const std::exception& e) {
        throw s.bad(e.what());
    }
    std::fprintf(stderr, "gonio-view: %s\n", app.notice().c_str());
}

void models_setting(App& app, ViewState& v, const Setting& s) {
    v.show.assign(app.model_count(), s.val == "all");
    if (s.val == "all" || s.val == "none") return;
    std::stringstream ss(s.val);
    std::string id;
    while (std::getline(ss, id, ',')) {
        size_t m = 0;
        while (m < app.model_count() && app.model_id(m) != id) ++m;
        if (m == app.model_count()) throw s.bad("no model '" + id + "' (see `gonio models`, or --model files)");
        v.show[m] = true;
    }
}

// A key of the stack (exterior_ior) or layer.N.KEY, a key of the layer's kind (stack_vocabulary.h), or
// layer.N.interface: the stack changed, or an invalid value keeps the previous stack and shows why.
void stack_setting(App& app, const Setting& s) {
    Stack st = app.stack();
    if (const StackKey* k = find_stack_key(s.key)) {
        st.*k->value = float(s.number());
    } else if (s.key.rfind("layer.", 0) == 0) {
        auto dot = s.key.find('.', 6);
        if (dot == std::string::npos) throw s.bad("expected layer.N.parameter");
        double n = s.number(s.key.substr(6, dot - 6));
        if (n < 1 || n > double(st.layers.size()) || n != std::floor(n))
            throw s.bad("the stack has layers 1 to " + std::to_string(st.layers.size()));
        Layer& L = st.layers[size_t(n) - 1];
        const std::string p = s.key.substr(dot + 1);
        if (p == "interface") {
            const KindInfo* k = find_kind(s.val);
            if (!k) throw s.bad("interface is one of " + kind_names());
            L.kind = k->kind;
        } else if (const LayerKey* key = find_layer_key(L.kind, p)) {
            key->set(L, key->shape == KeyShape::Number ? glm::vec3(float(s.number())) : s.rgb());
        } else if (is_layer_key(p)) {
            throw s.bad("'" + p + "' is not a key of a " + to_string(L.kind) + " layer");
        } else {
            throw s.bad("unknown layer parameter '" + p + "'");
        }
    } else {
        throw s.bad("unknown key; keys:\n" + settings_help());
    }
    app.set_stack(st, "--set " + s.kv);
}

}   // namespace

void apply_setting(App& app, ViewState& v, const std::string& kv) {
    auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--set " + kv + ": expected key=value");
    const Setting s{kv, kv.substr(0, eq), kv.substr(eq + 1)};
    if (view_setting(app, v, s)) return;
    if (s.key == "save") return save_setting(app, v, s);
    if (s.key == "models") return models_setting(app, v, s);
    stack_setting(app, s);
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
    const float light_phi = float(app.phi_i() * M_PI / 180.0);
    ImGui::BeginGroup();
    hemisphere_panel(v, hemi, HemisphereParams{colours.reference(), light, light_phi}, size, "reference",
                     IM_COL32(240, 240, 240, 255));
    // the legend, wrapped to the panel's width so that every column is as wide as its panel
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + std::max(size, 1.0f));
    ImGui::TextWrapped("%.3g M paths, median relative standard error %.2g%% (bins above 1%% of the peak)",
                       double(d.paths) * 1e-6, d.median_rse[side] * 100.0);
    ImGui::TextWrapped("%s, %s, %s.%s", side == 0 ? "BRDF seen from above" : "BTDF seen from above",
                       kChannelNames[v.channel], v.remap ? "log(1 + sqrt f)" : "f",
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
        hemisphere_panel(v, hemi, HemisphereParams{colours.model(i), light, light_phi}, size, id.c_str(),
                         model_colour(m));
        std::string dl = id + " - reference";
        hemisphere_panel(v, hemi, HemisphereParams{colours.difference(i), light, light_phi}, size, dl.c_str(),
                         model_colour(m));
        ImGui::EndGroup();
    }
    // the slice plot and the albedos
    const ImVec2 rest = ImGui::GetContentRegionAvail();
    const float table_w = std::min(300.0f, rest.x * 0.35f);
    ImGui::BeginGroup();
    ImGui::Text("in-plane slice (%s, theta_o < 0: the light's side), reference dashed",
                v.channel == 0 ? "luminance" : kChannelNames[v.channel]);
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
            for (int c = 0; c < kChannels; ++c) {
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
