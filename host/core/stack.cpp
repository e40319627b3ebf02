// Stack files: parsing (toml++), validation, description and serialisation. See stack.h.
#include "stack.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>

namespace gonio {

const char* to_string(InterfaceKind k) {
    switch (k) {
        case InterfaceKind::Dielectric:
            return "dielectric";
        case InterfaceKind::Conductor:
            return "conductor";
        case InterfaceKind::Lambertian:
            return "lambertian";
    }
    return "unknown";
}

bool Stack::transmissive() const { return !layers.empty() && layers.back().kind == InterfaceKind::Dielectric; }

bool Stack::medium_scatters(size_t i) const {
    const Layer& y = layers.at(i);
    if (y.kind != InterfaceKind::Dielectric || i + 1 == layers.size()) return false;
    for (int c = 0; c < 3; ++c)
        if (y.optical_depth[c] > 0.0f && y.scattering_albedo[c] > 0.0f) return true;
    return false;
}

glm::vec3 Stack::ior_above(size_t i) const { return i == 0 ? glm::vec3(exterior_ior) : layers.at(i - 1).ior; }

namespace {

// Shortest text that reads back to exactly the same float (valid TOML number when finite).
std::string num(float v) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

std::string num(double v) {
    char buf[40];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

bool uniform(glm::vec3 v) { return v.x == v.y && v.y == v.z; }

// "0.1" when the three channels are equal, "[0.1, 0.2, 0.3]" otherwise.
std::string rgb(glm::vec3 v) {
    if (uniform(v)) return num(v.x);
    return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]";
}

std::string fixed(float v, int digits) {
    std::ostringstream os;
    os.setf(std::ios::fixed);
    os.precision(digits);
    os << v;
    return os.str();
}

std::string rgb_fixed(glm::vec3 v, int digits) {
    if (uniform(v)) return fixed(v.x, digits);
    return "[" + fixed(v.x, digits) + ", " + fixed(v.y, digits) + ", " + fixed(v.z, digits) + "]";
}

std::string toml_string(std::string_view s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                if ((unsigned char)c < 0x20 || c == 0x7f) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", (unsigned)(unsigned char)c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

const char* type_name(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::string:
            return "a string";
        case toml::node_type::integer:
            return "an integer";
        case toml::node_type::floating_point:
            return "a number";
        case toml::node_type::boolean:
            return "a boolean";
        case toml::node_type::date:
            return "a date";
        case toml::node_type::time:
            return "a time";
        case toml::node_type::date_time:
            return "a date-time";
        case toml::node_type::array:
            return "an array";
        case toml::node_type::table:
            return "a table";
        default:
            return "nothing";
    }
}

// Lines to name in messages for each value of a stack (0 = unknown).
struct LayerLines {
    int layer = 0, roughness = 0, ior = 0, k = 0, optical_depth = 0, scattering_albedo = 0, phase_g = 0, albedo = 0;
};
struct StackLines {
    int name = 0, exterior = 0, layers_key = 0;
    std::vector<LayerLines> layers;
};

// The value rules, shared by validate_stack (layer lines only) and the parsers (each key's line).
void check(const Stack& s, const StackLines& L) {
    auto fail = [&](int line, const std::string& m) { throw StackError(s.source_path, line, m); };
    if (s.name.empty()) fail(L.name, "name must not be empty");
    if (!std::isfinite(s.exterior_ior) ||
        !(s.exterior_ior >= kExteriorIorRange.lo && s.exterior_ior <= kExteriorIorRange.hi))
        fail(L.exterior, "exterior_ior must be in [" + num(kExteriorIorRange.lo) + ", " + num(kExteriorIorRange.hi) +
                             "] (absolute IOR of the medium above the stack, 1 for air), got " + num(s.exterior_ior));
    const size_t n = s.layers.size();
    if (n == 0) fail(L.layers_key, "no layers: a stack needs at least one [[layer]] section");
    if (n > size_t(kMaxLayers))
        fail(L.layers[kMaxLayers].layer, "too many layers: a stack may have at most " + std::to_string(kMaxLayers) +
                                             " layers, got " + std::to_string(n));

    for (size_t i = 0; i < n; ++i) {
        const Layer& y = s.layers[i];
        const LayerLines& l = L.layers[i];
        const std::string pre = "layer " + std::to_string(i + 1) + ": ";
        const bool last = i + 1 == n;
        // Each channel of v must be finite and in the parameter's range (stack.h).
        auto channels = [&](int line, const char* what, glm::vec3 v, ParameterRange r, const char* why) {
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(v[c])) fail(line, pre + what + " must be a finite number, got " + rgb(v));
            for (int c = 0; c < 3; ++c)
                if (!(v[c] >= r.lo && v[c] <= r.hi))
                    fail(line,
                         pre + what + " must be in [" + num(r.lo) + ", " + num(r.hi) + "]" + why + ", got " + rgb(v));
        };
        auto roughness = [&] {
            if (y.roughness == 0.0f) return;   // smooth: a delta interface
            channels(l.roughness, "roughness", glm::vec3(y.roughness), kRoughnessRange,
                     " or 0 (GGX alpha; 0 is a smooth interface, below 1e-4 the lobe is narrower than float precision "
                     "resolves)");
        };
        if (y.kind != InterfaceKind::Dielectric && !last)
            fail(l.layer, pre + "misplaced base: a " + to_string(y.kind) +
                              " interface is opaque and must be the last layer (this is layer " +
                              std::to_string(i + 1) + " of " + std::to_string(n) + ")");
        switch (y.kind) {
            case InterfaceKind::Dielectric:
                roughness();
                channels(l.ior, "ior", y.ior, kDielectricIorRange, " (absolute IOR of the medium under the interface)");
                if (!uniform(y.ior))
                    fail(l.ior, pre +
                                    "per-channel dielectric IOR (dispersion) is not supported: refraction directions "
                                    "would differ per channel, so give one number (got " +
                                    rgb(y.ior) + ")");
                channels(l.optical_depth, "optical_depth", y.optical_depth, kOpticalDepthRange,
                         " (extinction optical depth tau = sigma_t * d)");
                channels(l.scattering_albedo, "scattering_albedo", y.scattering_albedo, kAlbedoRange,
                         " (single-scattering albedo sigma_s / sigma_t; above 1 a medium would create light)");
                if (!std::isfinite(y.phase_g) || !(y.phase_g > kPhaseGRange.lo && y.phase_g < kPhaseGRange.hi))
                    fail(l.phase_g, pre +
                                        "phase_g must be in (-1, 1) (Henyey-Greenstein asymmetry: 0 isotropic, > 0 "
                                        "forward; at +-1 the phase function is a delta), got " +
                                        num(y.phase_g));
                if (last && y.optical_depth != glm::vec3(0))
                    fail(
                        l.optical_depth,
                        pre + "optical_depth must be 0 on the last layer, got " + rgb(y.optical_depth) +
                            ": a dielectric last layer is the substrate interface of a transmissive stack, and the "
                            "substrate under a transmissive stack is semi-infinite, optical_depth has no meaning there");
                if (last && (y.scattering_albedo != glm::vec3(0) || y.phase_g != 0.0f))
                    fail(y.scattering_albedo != glm::vec3(0) ? l.scattering_albedo : l.phase_g,
                         pre +
                             "scattering_albedo and phase_g must be absent on the last layer: a dielectric last "
                             "layer is the substrate interface of a transmissive stack, and the substrate has no "
                             "medium of finite depth");
                break;
            case InterfaceKind::Conductor:
                roughness();
                channels(l.ior, "ior", y.ior, kConductorIorRange, " (real part of the conductor's complex IOR)");
                channels(l.k, "k", y.k, kConductorKRange,
                         " (extinction coefficient, imaginary part of the complex IOR)");
                break;
            case InterfaceKind::Lambertian:
                channels(
                    l.albedo, "albedo", y.albedo, kAlbedoRange,
                    " (an albedo above 1 would reflect more light than it receives: non-physical; nothing is clamped)");
                break;
            default:
                fail(l.layer, pre + "invalid interface kind " + std::to_string(int(y.kind)));
        }
    }
}

// ----- parser ------------------------------------------------------------------------------------

constexpr std::string_view kTopKeys = "name, description, exterior_ior, layer";
constexpr std::string_view kKinds = "dielectric, conductor, lambertian";
constexpr std::array<std::string_view, 8> kLayerKeys{"interface",     "roughness",         "ior",     "k",
                                                     "optical_depth", "scattering_albedo", "phase_g", "albedo"};

std::vector<std::string_view> keys_for(InterfaceKind k) {
    switch (k) {
        case InterfaceKind::Dielectric:
            return {"interface", "roughness", "ior", "optical_depth", "scattering_albedo", "phase_g"};
        case InterfaceKind::Conductor:
            return {"interface", "roughness", "ior", "k"};
        default:
            return {"interface", "albedo"};
    }
}

std::string join(const std::vector<std::string_view>& v) {
    std::string s;
    for (auto x : v) s += (s.empty() ? "" : ", ") + std::string(x);
    return s;
}

int line_of(const toml::node& n, int fallback = 0) {
    int l = int(n.source().begin.line);
    return l > 0 ? l : fallback;
}

int line_of(const toml::key& k, const toml::node& n) {
    int l = int(k.source().begin.line);
    return l > 0 ? l : line_of(n);
}

struct Parser {
    std::string path;

    [[noreturn]] void fail(int line, const std::string& m) const { throw StackError(path, line, m); }

    // A single number (integer or float), finite and representable as a float.
    float number(const toml::node& n, const std::string& what, int fallback) const {
        const int line = line_of(n, fallback);
        double v = 0;
        if (auto i = n.as_integer())
            v = double(i->get());
        else if (auto f = n.as_floating_point())
            v = f->get();
        else
            fail(line, what + " must be a number, got " + type_name(n));
        if (std::isnan(v)) fail(line, what + " must be a finite number, got nan");
        if (std::isinf(v)) fail(line, what + " must be a finite number, got " + (v > 0 ? "inf" : "-inf"));
        if (std::abs(v) > double(std::numeric_limits<float>::max()))
            fail(line, what + " is out of range for a 32-bit float, got " + num(v));
        return float(v);
    }

    // A number (broadcast to the three channels) or an array of exactly 3 numbers (R, G, B).
    glm::vec3 color(const toml::node& n, const std::string& what, int fallback) const {
        const int line = line_of(n, fallback);
        if (auto a = n.as_array()) {
            if (a->size() != 3)
                fail(line, what + ": wrong array length: expected a number or an array of 3 numbers, got " +
                               std::to_string(a->size()));
            glm::vec3 v;
            for (int c = 0; c < 3; ++c) v[c] = number(*a->get(size_t(c)), what + "[" + std::to_string(c) + "]", line);
            return v;
        }
        if (!n.is_number())
            fail(line, what + " must be a number or an array of 3 numbers (R, G, B), got " + type_name(n));
        return glm::vec3(number(n, what, line));
    }

    Layer layer(const toml::table& t, size_t i, int fallback, LayerLines& ll) const {
        Layer y;
        int tl = line_of(t);
        if (tl == 0) {   // no region for the table: use its first key's line
            for (auto&& [key, node] : t) {
                int kl = line_of(key, node);
                if (kl > 0 && (tl == 0 || kl < tl)) tl = kl;
            }
        }
        if (tl == 0) tl = fallback;
        y.line = ll.layer = ll.roughness = ll.ior = ll.k = ll.optical_depth = ll.scattering_albedo = ll.phase_g =
            ll.albedo = tl;
        const std::string pre = "layer " + std::to_string(i + 1) + ": ";

        const toml::node* in = t.get("interface");
        if (!in) fail(tl, pre + "missing required key 'interface' (one of " + std::string(kKinds) + ")");
        if (!in->is_string())
            fail(line_of(*in, tl),
                 pre + "interface must be a string, one of " + std::string(kKinds) + "; got " + type_name(*in));
        const auto kind_name = in->value<std::string>();
        if (*kind_name == "dielectric")
            y.kind = InterfaceKind::Dielectric;
        else if (*kind_name == "conductor")
            y.kind = InterfaceKind::Conductor;
        else if (*kind_name == "lambertian")
            y.kind = InterfaceKind::Lambertian;
        else
            fail(line_of(*in, tl),
                 pre + "unknown interface '" + *kind_name + "'; expected one of " + std::string(kKinds));

        const auto allowed = keys_for(y.kind);
        const std::string kind = to_string(y.kind);
        for (auto&& [key, node] : t) {
            const std::string_view k = key.str();
            if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
            const int kl = line_of(key, node) ? line_of(key, node) : tl;
            if (std::find(kLayerKeys.begin(), kLayerKeys.end(), k) != kLayerKeys.end())
                fail(kl, pre + "key '" + std::string(k) + "' does not apply to a " + kind + " interface (keys of a " +
                             kind + " layer: " + join(allowed) + ")");
            fail(kl, pre + "unknown key '" + std::string(k) + "'; allowed keys for a " + kind +
                         " interface: " + join(allowed));
        }

        auto required = [&](const char* key, const std::string& what) -> const toml::node& {
            const toml::node* n = t.get(key);
            if (!n) fail(tl, pre + "missing required key '" + key + "' (" + what + ")");
            return *n;
        };
        auto key_line = [&](const char* key) {
            for (auto&& [k, node] : t)
                if (k.str() == key) return line_of(k, node) ? line_of(k, node) : tl;
            return tl;
        };
        if (const toml::node* r = t.get("roughness")) {
            ll.roughness = key_line("roughness");
            if (r->is_array())
                fail(ll.roughness,
                     pre + "roughness must be a single number (GGX alpha, the same for all channels), got an array");
            y.roughness = number(*r, pre + "roughness", ll.roughness);
        }
        switch (y.kind) {
            case InterfaceKind::Dielectric:
                y.ior =
                    color(required("ior", "absolute IOR of the medium under the interface, a number in [" +
                                              num(kDielectricIorRange.lo) + ", " + num(kDielectricIorRange.hi) + "]"),
                          pre + "ior", ll.ior = key_line("ior"));
                if (const toml::node* d = t.get("optical_depth"))
                    y.optical_depth = color(*d, pre + "optical_depth", ll.optical_depth = key_line("optical_depth"));
                if (const toml::node* a = t.get("scattering_albedo"))
                    y.scattering_albedo =
                        color(*a, pre + "scattering_albedo", ll.scattering_albedo = key_line("scattering_albedo"));
                if (const toml::node* g = t.get("phase_g")) {
                    ll.phase_g = key_line("phase_g");
                    if (g->is_array())
                        fail(ll.phase_g, pre +
                                             "phase_g must be a single number (the Henyey-Greenstein asymmetry, "
                                             "the same for all channels), got an array");
                    y.phase_g = number(*g, pre + "phase_g", ll.phase_g);
                }
                break;
            case InterfaceKind::Conductor:
                y.ior = color(required("ior", "real part of the complex IOR: a number or an array of 3 numbers in [" +
                                                  num(kConductorIorRange.lo) + ", " + num(kConductorIorRange.hi) + "]"),
                              pre + "ior", ll.ior = key_line("ior"));
                y.k = color(required("k",
                                     "extinction coefficient, imaginary part of the complex IOR: a number or an "
                                     "array of 3 numbers in [" +
                                         num(kConductorKRange.lo) + ", " + num(kConductorKRange.hi) + "]"),
                            pre + "k", ll.k = key_line("k"));
                break;
            case InterfaceKind::Lambertian:
                y.albedo = color(required("albedo", "diffuse albedo: a number or an array of 3 numbers in [0, 1]"),
                                 pre + "albedo", ll.albedo = key_line("albedo"));
                break;
        }
        return y;
    }

    Stack stack(const std::string& text) const {
        toml::table t;
        try {
            t = toml::parse(text, path);
        } catch (const toml::parse_error& e) {
            throw StackError(path, int(e.source().begin.line), "invalid TOML: " + std::string(e.description()));
        }
        Stack s;
        s.source_path = path;
        s.source_text = text;
        StackLines L;
        L.name = L.exterior = L.layers_key = 1;   // whole-file problems (a missing key) are reported at line 1

        for (auto&& [key, node] : t) {
            const std::string_view k = key.str();
            if (k != "name" && k != "description" && k != "exterior_ior" && k != "layer")
                fail(line_of(key, node),
                     "unknown key '" + std::string(k) + "'; allowed top-level keys: " + std::string(kTopKeys));
        }

        const toml::node* name = t.get("name");
        if (!name) fail(1, "missing required key 'name' (the stack's name, a non-empty string)");
        L.name = line_of(*name, 1);
        if (!name->is_string()) fail(L.name, std::string("name must be a string, got ") + type_name(*name));
        s.name = name->as_string()->get();

        if (const toml::node* d = t.get("description")) {
            if (!d->is_string())
                fail(line_of(*d, 1), std::string("description must be a string, got ") + type_name(*d));
            s.description = d->as_string()->get();
        }

        if (const toml::node* e = t.get("exterior_ior")) {
            L.exterior = line_of(*e, 1);
            if (e->is_array())
                fail(L.exterior,
                     "exterior_ior must be a single number > 0 (the medium above the stack is one dielectric, "
                     "the same for all channels), got an array");
            s.exterior_ior = number(*e, "exterior_ior", L.exterior);
        }

        const toml::node* ln = t.get("layer");
        if (!ln) fail(1, "no layers: a stack needs at least one [[layer]] section");
        L.layers_key = line_of(*ln, 1);
        const toml::array* arr = ln->as_array();
        if (!arr)
            fail(L.layers_key,
                 std::string("'layer' must be an array of tables (write each layer as a [[layer]] section), got ") +
                     type_name(*ln));
        for (size_t i = 0; i < arr->size(); ++i) {
            const toml::node& e = *arr->get(i);
            const toml::table* lt = e.as_table();
            if (!lt)
                fail(line_of(e, L.layers_key),
                     "layer " + std::to_string(i + 1) + " must be a table (a [[layer]] section), got " + type_name(e));
            if (i == size_t(kMaxLayers))   // report at the first layer too many, before looking into it
                fail(line_of(e, L.layers_key), "too many layers: a stack may have at most " +
                                                   std::to_string(kMaxLayers) + " layers, got " +
                                                   std::to_string(arr->size()));
            L.layers.emplace_back();
            s.layers.push_back(layer(*lt, i, L.layers_key, L.layers.back()));
        }
        check(s, L);
        return s;
    }
};

}   // namespace

Stack parse_stack_string(const std::string& text, const std::string& path_for_messages) {
    return Parser{path_for_messages}.stack(text);
}

Stack parse_stack_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw StackError(path, 0, "cannot open the stack file for reading");
    std::ostringstream text;
    text << f.rdbuf();
    return parse_stack_string(text.str(), path);
}

void validate_stack(const Stack& s) {
    StackLines L;
    for (const Layer& y : s.layers) {
        LayerLines& l = L.layers.emplace_back();
        l.layer = l.roughness = l.ior = l.k = l.optical_depth = l.scattering_albedo = l.phase_g = l.albedo = y.line;
    }
    check(s, L);
}

bool layer_key_applies(InterfaceKind kind, const std::string& key) {
    if (key == "interface") return false;
    for (std::string_view k : keys_for(kind))
        if (k == key) return true;
    return false;
}

std::string describe_stack(const Stack& s) {
    std::ostringstream o;
    o << "stack '" << s.name << "'";
    if (!s.source_path.empty()) o << " (" << s.source_path << ")";
    o << "\n";
    if (!s.description.empty()) o << "  " << s.description << "\n";
    o << "  exterior medium: ior " << num(s.exterior_ior) << "\n";
    o << "  " << s.layers.size() << (s.layers.size() == 1 ? " layer" : " layers") << ", top to bottom:\n";
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& y = s.layers[i];
        const bool last = i + 1 == s.layers.size();
        const float na = s.ior_above(i).x;
        o << "  layer " << i + 1;
        if (y.line > 0) o << " (line " << y.line << ")";
        o << ": " << to_string(y.kind) << (y.kind == InterfaceKind::Dielectric ? " interface" : " base");
        if (y.kind != InterfaceKind::Lambertian)
            o << ", GGX roughness " << num(y.roughness) << (y.roughness == 0 ? " (perfectly smooth)" : "");
        o << "\n";
        switch (y.kind) {
            case InterfaceKind::Dielectric: {
                const float nb = y.ior.x;
                if (last) {
                    o << "      below: semi-infinite substrate, ior " << num(nb) << "\n";
                } else {
                    o << "      medium below: ior " << num(nb) << ", optical depth " << rgb(y.optical_depth);
                    o << " (transmittance at normal incidence " << rgb_fixed(glm::exp(-y.optical_depth), 3) << ")\n";
                    if (s.medium_scatters(i))
                        o << "      scattering: single-scattering albedo " << rgb(y.scattering_albedo)
                          << ", Henyey-Greenstein g " << num(y.phase_g) << " (scattering optical depth "
                          << rgb(y.optical_depth * y.scattering_albedo) << ", absorption "
                          << rgb(y.optical_depth * (glm::vec3(1.0f) - y.scattering_albedo)) << ")\n";
                    else if (y.scattering_albedo != glm::vec3(0) || y.phase_g != 0.0f)
                        o << "      scattering_albedo " << rgb(y.scattering_albedo) << ", phase_g " << num(y.phase_g)
                          << ": no effect (nothing scatters where the optical depth or the albedo is 0)\n";
                }
                o << "      eta = n_below/n_above = " << num(nb) << "/" << num(na) << " = " << fixed(nb / na, 4);
                if (nb > na)
                    o << "; total internal reflection for light arriving from below beyond the critical angle "
                      << fixed(float(std::asin(na / nb) * 180.0 / std::numbers::pi), 2) << " deg\n";
                else if (nb < na)
                    o << "; total internal reflection for light arriving from above beyond the critical angle "
                      << fixed(float(std::asin(nb / na) * 180.0 / std::numbers::pi), 2) << " deg\n";
                else
                    o << "; index-matched: no refraction, no total internal reflection\n";
                break;
            }
            case InterfaceKind::Conductor:
                o << "      complex ior " << rgb(y.ior) << " + i " << rgb(y.k) << "\n";
                o << "      eta = (n + i k)/n_above = " << rgb_fixed(y.ior / na, 4) << " + i " << rgb_fixed(y.k / na, 4)
                  << "\n";
                break;
            case InterfaceKind::Lambertian:
                o << "      albedo " << rgb(y.albedo) << "\n";
                break;
        }
    }
    if (s.layers.empty())
        o << "  (no layers)\n";
    else if (s.transmissive())
        o << "  transmissive: light can leave through the bottom into the substrate (reflection and transmission)\n";
    else
        o << "  opaque: the " << to_string(s.base().kind)
          << " base stops all light; it leaves only through the top (reflection only)\n";
    return o.str();
}

std::string stack_to_toml(const Stack& s) {
    std::ostringstream o;
    o << "name = " << toml_string(s.name) << "\n";
    o << "description = " << toml_string(s.description) << "\n";
    o << "exterior_ior = " << num(s.exterior_ior) << "\n";
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& y = s.layers[i];
        o << "\n[[layer]]\n";
        o << "interface = \"" << to_string(y.kind) << "\"\n";
        switch (y.kind) {
            case InterfaceKind::Dielectric:
                o << "roughness = " << num(y.roughness) << "\n";
                o << "ior = " << rgb(y.ior) << "\n";
                if (i + 1 < s.layers.size() || y.optical_depth != glm::vec3(0))
                    o << "optical_depth = " << rgb(y.optical_depth) << "\n";
                if (y.scattering_albedo != glm::vec3(0))
                    o << "scattering_albedo = " << rgb(y.scattering_albedo) << "\n";
                if (y.phase_g != 0.0f) o << "phase_g = " << num(y.phase_g) << "\n";
                break;
            case InterfaceKind::Conductor:
                o << "roughness = " << num(y.roughness) << "\n";
                o << "ior = " << rgb(y.ior) << "\n";
                o << "k = " << rgb(y.k) << "\n";
                break;
            case InterfaceKind::Lambertian:
                o << "albedo = " << rgb(y.albedo) << "\n";
                break;
        }
    }
    return o.str();
}

}   // namespace gonio
