// Stack files: parsing (toml++), validation, description and serialisation. See stack.h.
#include "stack.h"
#include "input_file.h"
#include "colorimetry.h"
#include "glasses.h"
#include "measured_materials.h"
#include "stack_vocabulary.h"
#include "text_format.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>

namespace gonio {

const char* to_string(InterfaceKind k) { return kind_info(k).name; }

bool Layer::material_intact() const {
    const MeasuredConductor* c = material.empty() ? nullptr : find_measured_conductor(material);
    if (!c) return false;
    const ConductorRgb rgb = conductor_rgb(*c);
    return ior == glm::vec3(float(rgb.n[0]), float(rgb.n[1]), float(rgb.n[2])) &&
           k == glm::vec3(float(rgb.k[0]), float(rgb.k[1]), float(rgb.k[2]));
}

const KeySpectrum* Layer::intact_spectrum(const std::string& name, glm::vec3 value) const {
    for (const KeySpectrum& k : spectra)
        if (k.key == name) return k.rgb == value ? &k : nullptr;
    return nullptr;
}

bool Stack::transmissive() const { return !layers.empty() && layers.back().kind == InterfaceKind::Dielectric; }

bool Stack::medium_scatters(size_t i) const {
    const Layer& y = layers.at(i);
    if (y.kind != InterfaceKind::Dielectric || i + 1 == layers.size()) return false;
    for (int c = 0; c < kChannels; ++c)
        if (y.optical_depth[c] > 0.0f && (y.scattering_albedo[c] > 0.0f || y.phase != MediumPhase::Hg)) return true;
    return false;
}

glm::vec3 Stack::ior_above(size_t i) const { return i == 0 ? glm::vec3(exterior_ior) : layers.at(i - 1).ior; }

namespace {

// Shortest text that reads back to exactly the same float (valid TOML number when finite).
std::string num(float v) { return format_shortest(v); }

std::string num(double v) {
    char buf[40];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

bool uniform(glm::vec3 v) { return v.x == v.y && v.y == v.z; }

// The layer's word for a word key ("sggx-fibre")
std::string choice_word(std::string_view key, const Layer& y) {
    const ChoiceKey& c = *find_choice_key(key);
    return c.words[size_t(c.get(y))];
}

// "0.1" when the three channels are equal, "[0.1, 0.2, 0.3]" otherwise.
std::string rgb(glm::vec3 v) {
    if (uniform(v)) return num(v.x);
    return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]";
}

// A value computed from the keys (not one as written), to 6 significant digits: 0.1 x 0.3 is "0.03", not the float
// product's "0.030000001".
std::string derived(glm::vec3 v) {
    auto g6 = [](float x) {
        char b[32];
        std::snprintf(b, sizeof b, "%.6g", double(x));
        return std::string(b);
    };
    if (uniform(v)) return g6(v.x);
    return "[" + g6(v.x) + ", " + g6(v.y) + ", " + g6(v.z) + "]";
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

// Lines to name in messages for each value of a stack (0 = unknown): a layer's [[layer]] header and each key's
// (indexed as layer_keys()).
struct LayerLines {
    int layer = 0;
    std::vector<int> key;
    explicit LayerLines(int line = 0) : layer(line), key(layer_keys().size(), line) {}
    int of(const LayerKey& y) const { return key[size_t(&y - layer_keys().data())]; }
    int& of(const LayerKey& y) { return key[size_t(&y - layer_keys().data())]; }
};
struct StackLines {
    int name = 0, exterior = 0, layers_key = 0;
    std::vector<LayerLines> layers;
};

[[noreturn]] void fail_at(const Stack& s, int line, const std::string& m) { throw StackError(s.source_path, line, m); }

// A key's value against its range (stack_vocabulary.h): every channel finite and in it.
void check_key(const Stack& s, const LayerKey& key, glm::vec3 v, int line, const std::string& pre) {
    if (key.or_zero && v == glm::vec3(0.0f)) return;
    const std::string got = ", got " + rgb(v);
    for (int c = 0; c < kChannels; ++c)
        if (!std::isfinite(v[c])) fail_at(s, line, pre + key.name + " must be a finite number" + got);
    for (int c = 0; c < kChannels; ++c) {
        if (!key.admits(v[c]))
            fail_at(s, line, pre + key.name + " must be in " + key.range_text() + " (" + key.meaning + ")" + got);
    }
    if (key.one_value && !uniform(v))
        fail_at(s, line,
                pre + "per-channel " + to_string(key.kind) + " " + key.name +
                    " (dispersion) is not supported: refraction directions would differ per channel, so give one "
                    "number, or a spectrum of pairs [nm, n] for a spectral run (got " +
                    rgb(v) + ")");
}

// A dielectric last layer is the substrate interface of a transmissive stack: no medium under it.
void check_substrate(const Stack& s, const Layer& y, const LayerLines& l, const std::string& pre) {
    for (const LayerKey* key : keys_of(y.kind))
        if (key->medium && key->get(y) != glm::vec3(key->fallback))
            fail_at(s, l.of(*key),
                    pre + key->name + " must be absent (or " + num(key->fallback) + ") on the last layer, got " +
                        rgb(key->get(y)) +
                        ": a dielectric last layer is the substrate interface of a transmissive stack, and the "
                        "substrate under a transmissive stack is semi-infinite, " +
                        key->name + " has no meaning there");
}

// A medium's phase function and the keys that belong to it: fibre_roughness to a microflake medium (where it is
// required), phase_g to a Henyey-Greenstein one; none on a substrate.
void check_phase(const Stack& s, const Layer& y, const LayerLines& l, const std::string& pre, bool last) {
    if (y.kind != InterfaceKind::Dielectric) return;
    const std::string word = choice_word("phase", y);
    const LayerKey& fibre = *find_layer_key(y.kind, "fibre_roughness");
    const LayerKey& g = *find_layer_key(y.kind, "phase_g");
    if (last && y.phase != MediumPhase::Hg)
        fail_at(s, l.layer,
                pre + "phase must be absent (or \"hg\") on the last layer, got \"" + word +
                    "\": a dielectric last layer is the substrate interface of a transmissive stack, with no medium "
                    "under it");
    if (last) return;
    if (y.phase != MediumPhase::Hg && y.fibre_roughness == 0.0f)
        fail_at(s, l.layer,
                pre + "phase = \"" + word + "\" needs fibre_roughness, the microflakes' roughness alpha in [" +
                    num(fibre.range.lo) + ", " + num(fibre.range.hi) +
                    "] (sigma = alpha^2, the fibres' cross-section)");
    if (y.phase == MediumPhase::Hg && y.fibre_roughness != 0.0f)
        fail_at(s, l.of(fibre),
                pre +
                    "fibre_roughness is a microflake medium's key, and this medium's phase is \"hg\" "
                    "(Henyey-Greenstein); give phase = \"sggx-fibre\" or \"sggx-flake\" with it, got "
                    "fibre_roughness " +
                    num(y.fibre_roughness));
    if (y.phase != MediumPhase::Hg && y.phase_g != 0.0f)
        fail_at(s, l.of(g),
                pre + "phase_g is Henyey-Greenstein's asymmetry, and this medium's phase is \"" + word +
                    "\" (its flakes scatter specularly; fibre_roughness shapes them), got phase_g " + num(y.phase_g));
}

// The value rules, shared by validate_stack (layer lines only) and the parsers (each key's line).
void check(const Stack& s, const StackLines& L) {
    if (s.name.empty()) fail_at(s, L.name, "name must not be empty");
    for (const StackKey& k : stack_keys()) {
        const float v = s.*k.value;
        if (!std::isfinite(v) || !(v >= k.range.lo && v <= k.range.hi))
            fail_at(s, L.exterior,
                    std::string(k.name) + " must be in " + k.range_text() + " (" + k.meaning + "), got " + num(v));
    }
    const size_t n = s.layers.size();
    if (n == 0) fail_at(s, L.layers_key, "no layers: a stack needs at least one [[layer]] section");
    if (n > size_t(kMaxLayers))
        fail_at(s, L.layers[kMaxLayers].layer,
                "too many layers: a stack may have at most " + std::to_string(kMaxLayers) + " layers, got " +
                    std::to_string(n));
    for (size_t i = 0; i < n; ++i) {
        const Layer& y = s.layers[i];
        const LayerLines& l = L.layers[i];
        const std::string pre = "layer " + std::to_string(i + 1) + ": ";
        const bool last = i + 1 == n;
        if (std::none_of(interface_kinds().begin(), interface_kinds().end(),
                         [&](const KindInfo& k) { return k.kind == y.kind; }))
            fail_at(s, l.layer, pre + "invalid interface kind " + std::to_string(int(y.kind)));
        if (kind_info(y.kind).opaque && !last)
            fail_at(s, l.layer,
                    pre + "misplaced base: a " + to_string(y.kind) +
                        " interface is opaque and must be the last layer (this is layer " + std::to_string(i + 1) +
                        " of " + std::to_string(n) + ")");
        for (const LayerKey* key : keys_of(y.kind)) check_key(s, *key, key->get(y), l.of(*key), pre);
        if (last && !kind_info(y.kind).opaque) check_substrate(s, y, l, pre);
        check_phase(s, y, l, pre, last);
        if (y.microfacets == Microfacets::Multiple && y.shadowing == Shadowing::Separable)
            fail_at(s, l.layer,
                    pre +
                        "shadowing = \"separable\" cannot be given with microfacets = \"multiple\": the walk on "
                        "the microsurface is height-correlated by construction (Heitz et al. 2016, Sec. 4)");
    }
}

// ----- parser ------------------------------------------------------------------------------------

// The keys a [[layer]] of this kind takes ("interface" first, its names last).
std::vector<std::string_view> keys_for(InterfaceKind k) {
    std::vector<std::string_view> out{"interface"};
    for (const LayerKey* y : keys_of(k)) out.push_back(y->name);
    for (const NamedKey& n : named_keys())
        if (n.kind == k) out.push_back(n.name);
    for (const ChoiceKey& c : choice_keys())
        if (c.of_kind(k)) out.push_back(c.name);
    return out;
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

    // A name is text that outputs carry (file names, CSV and JSON fields, messages): no control characters (a NUL
    // cut `check`'s output); a description, free text written back escaped, no NUL
    void refuse_control_characters(const std::string& key, const std::string& text, int line) const {
        for (size_t i = 0; i < text.size(); ++i) {
            const unsigned char c = static_cast<unsigned char>(text[i]);
            if (key == "name" ? (c < 0x20 || c == 0x7f) : c == 0) {
                char code[8];
                std::snprintf(code, sizeof code, "%02X", c);
                fail(line, key + ": a control character (U+00" + code + ") at character " + std::to_string(i + 1) +
                               "; write it without one");
            }
        }
    }

    // A single number (integer or float) as written, finite and representable as a float.
    double number(const toml::node& n, const std::string& what, int fallback) const {
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
        return v + 0.0;   // -0 as 0: the same value, written back and printed as 0
    }

    // A number (broadcast to the three channels) or an array of exactly 3 numbers (R, G, B), as written.
    glm::dvec3 color(const toml::node& n, const std::string& what, int fallback) const {
        const int line = line_of(n, fallback);
        if (auto a = n.as_array()) {
            if (a->size() != 3)
                fail(line, what + ": wrong array length: expected a number or an array of 3 numbers, got " +
                               std::to_string(a->size()));
            glm::dvec3 v;
            for (int c = 0; c < kChannels; ++c)
                v[c] = number(*a->get(size_t(c)), what + "[" + std::to_string(c) + "]", line);
            return v;
        }
        if (!n.is_number())
            fail(line, what + " must be a number or an array of 3 numbers (R, G, B), got " + type_name(n));
        return glm::dvec3(number(n, what, line));
    }

    // A key's value as written checked against its range before a float holds it: 1.00000001 is not a roughness,
    // 0.99999999 is a phase_g that a float holds as 1.
    glm::vec3 in_range(const LayerKey& key, glm::dvec3 v, const std::string& what, int line) const {
        for (int c = 0; c < kChannels; ++c)
            if (!key.admits(v[c]))
                fail(line,
                     what + " must be in " + key.range_text() + " (" + key.meaning + "), got " +
                         (v.x == v.y && v.y == v.z ? written_value_text(v[c])
                                                   : "[" + written_value_text(v.x) + ", " + written_value_text(v.y) +
                                                         ", " + written_value_text(v.z) + "]"));
        return glm::vec3(v);
    }

    // The line of a [[layer]] table: its header's, else its first key's, else `fallback`.
    static int table_line(const toml::table& t, int fallback) {
        int tl = line_of(t);
        if (tl == 0) {   // no region for the table: use its first key's line
            for (auto&& [key, node] : t) {
                int kl = line_of(key, node);
                if (kl > 0 && (tl == 0 || kl < tl)) tl = kl;
            }
        }
        return tl == 0 ? fallback : tl;
    }

    InterfaceKind kind_of(const toml::table& t, int tl, const std::string& pre) const {
        const toml::node* in = t.get("interface");
        if (!in) fail(tl, pre + "missing required key 'interface' (one of " + kind_names() + ")");
        if (!in->is_string())
            fail(line_of(*in, tl),
                 pre + "interface must be a string, one of " + kind_names() + "; got " + type_name(*in));
        const auto name = in->value<std::string>();
        const KindInfo* k = find_kind(*name);
        if (!k) fail(line_of(*in, tl), pre + "unknown interface '" + *name + "'; expected one of " + kind_names());
        return k->kind;
    }

    // Every key of the table is one of the kind's.
    void only_keys_of(const toml::table& t, InterfaceKind kind, int tl, const std::string& pre) const {
        const auto allowed = keys_for(kind);
        const std::string k_name = to_string(kind);
        for (auto&& [key, node] : t) {
            const std::string_view k = key.str();
            if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
            const int kl = line_of(key, node) ? line_of(key, node) : tl;
            for (const NamedKey& n : named_keys())
                if (k == n.name)
                    fail(kl, pre + "key '" + n.name + "' does not apply to a " + k_name + " interface (a " +
                                 kind_info(n.kind).name + "'s name that gives its " + n.gives[0] + " and " +
                                 n.gives[1] + ": " + n.names() + ")");
            if (is_layer_key(k) || find_choice_key(k))
                fail(kl, pre + "key '" + std::string(k) + "' does not apply to a " + k_name + " interface (keys of a " +
                             k_name + " layer: " + join(allowed) + ")");
            fail(kl, pre + "unknown key '" + std::string(k) + "'; allowed keys for a " + k_name +
                         " interface: " + join(allowed));
        }
    }

    // A key's value as its shape reads it (stack_vocabulary.h); a required key that is absent is refused.
    void read_key(const toml::table& t, const LayerKey& key, Layer& y, int tl, int& line,
                  const std::string& pre) const {
        const toml::node* n = nullptr;
        for (auto&& [k, node] : t)
            if (k.str() == key.name) {
                n = &node;
                line = line_of(k, node) ? line_of(k, node) : tl;
            }
        const bool rgb_shape = key.shape == KeyShape::Rgb;
        if (!n) {
            if (key.required)
                fail(tl, pre + "missing required key '" + key.name + "' (" + key.meaning + ": " +
                             (rgb_shape ? "a number or an array of 3 numbers" : "a number") + " in " +
                             key.range_text() + ")");
            key.set(y, glm::vec3(key.fallback));
            return;
        }
        const std::string what = pre + key.name;
        if (!rgb_shape && n->is_array())
            fail(line,
                 what + " must be a single number, the same for all channels (" + key.meaning + "), got an array");
        const toml::array* a = n->as_array();
        if (rgb_shape && a && !a->empty() && a->get(0)->is_array()) {
            key.set(y, spectrum(*a, key, y, what, line));
            return;
        }
        if (key.one_value && (n->is_string() || n->is_table())) {   // a named glass or a dispersion formula
            key.set(y, dispersion(*n, key, y, what, line));
            return;
        }
        key.set(y, in_range(key, rgb_shape ? color(*n, what, line) : glm::dvec3(number(*n, what, line)), what, line));
    }

    // A key given as a spectrum: pairs [nm, value] in increasing wavelength, each value in the key's range, covering
    // the sRGB primaries' dominant wavelengths, where the RGB run reads it (its RGB value, returned).
    glm::vec3 spectrum(const toml::array& a, const LayerKey& key, Layer& y, const std::string& what, int line) const {
        if (a.size() < 2)
            fail(line, what + ": a spectrum needs at least 2 pairs [nm, value], got " + std::to_string(a.size()));
        SpectralTable t;
        t.file = what;
        t.columns = {"value"};
        t.values.resize(1);
        for (size_t i = 0; i < a.size(); ++i) {
            const toml::node& e = *a.get(i);
            const int el = line_of(e, line);
            const std::string wi = what + "[" + std::to_string(i) + "]";
            const toml::array* p = e.as_array();
            if (!p || p->size() != 2)
                fail(el, wi + ": expected a pair [nm, value] (a spectrum is an array of them), got " +
                             (p ? "an array of " + std::to_string(p->size()) : std::string(type_name(e))));
            const double nm = number(*p->get(0), wi + "'s wavelength", el);
            const double v = number(*p->get(1), wi + "'s value", el);
            if (!(nm > 0)) fail(el, wi + ": the wavelength must be above 0 nm, got " + num(float(nm)));
            if (!t.wavelength_nm.empty() && !(nm > t.wavelength_nm.back()))
                fail(el, wi + ": wavelengths must increase, got " + num(float(nm)) + " nm after " +
                             num(float(t.wavelength_nm.back())) + " nm");
            if (!key.admits(v))
                fail(el, wi + ": " + key.name + " must be in " + key.range_text() + " (" + key.meaning + "), got " +
                             written_value_text(v) + " at " + num(nm) + " nm");
            t.wavelength_nm.push_back(nm);
            t.values[0].push_back(v);
        }
        return spectral_value(std::move(t), key, y, what, line, "");
    }

    // A dielectric's IOR as a named glass (`ior = "N-BK7"`) or a formula (`ior = { sellmeier = [B1, B2, B3, C1, C2,
    // C3] }`, `ior = { cauchy = [A, B] }` or `[A, B, C]`, micrometres): tabulated from 300 to 900 nm at 2 nm (a named
    // glass only where its source says its formula holds), then as a spectrum.
    glm::vec3 dispersion(const toml::node& n, const LayerKey& key, Layer& y, const std::string& what, int line) const {
        std::function<double(double)> formula;
        std::string given;
        double first_nm = 300, last_nm = 900;
        if (const toml::value<std::string>* name = n.as_string()) {
            const NamedGlass* g = find_named_glass(name->get());
            if (!g)
                fail(line, what + ": unknown glass '" + name->get() + "'; known glasses: " + named_glass_names() +
                               " (or a number, pairs [nm, n], { sellmeier = [...] } or { cauchy = [...] })");
            formula = [g](double nm) { return g->formula.n(nm); };
            given = toml_string(name->get());
            first_nm =
                std::max(first_nm, 2 * std::ceil(g->first_nm / 2));   // on the 2 nm grid, within its source's range
            last_nm = std::min(last_nm, 2 * std::floor(g->last_nm / 2));
        } else {
            const toml::table& t = *n.as_table();
            if (t.size() != 1 || !(t.contains("sellmeier") || t.contains("cauchy")))
                fail(line, what +
                               ": a dispersion formula is { sellmeier = [B1, B2, B3, C1, C2, C3] } or { cauchy = "
                               "[A, B] } (or [A, B, C]; micrometres)");
            const bool sellmeier = t.contains("sellmeier");
            const toml::array* c = t.get(sellmeier ? "sellmeier" : "cauchy")->as_array();
            const size_t want = sellmeier ? 6 : 0;
            if (!c || (sellmeier ? c->size() != want : (c->size() != 2 && c->size() != 3)))
                fail(line, what + (sellmeier ? ": sellmeier takes 6 numbers, B1, B2, B3, C1, C2, C3 (C in square "
                                               "micrometres)"
                                             : ": cauchy takes 2 or 3 numbers, A, B (, C) (micrometres)"));
            std::vector<double> v;
            for (size_t i = 0; i < c->size(); ++i)
                v.push_back(number(*c->get(i), what + "[" + std::to_string(i) + "]", line));
            if (sellmeier) {
                Sellmeier f{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
                // n^2 = 1 + sum B lambda^2 / (lambda^2 - C): a pole at lambda = sqrt(C) may fall between the 2 nm
                // points the table checks, so a pole in the range is refused as such
                for (int i = 0; i < 3; ++i) {
                    const double pole_nm = v[3 + i] > 0 ? 1000 * std::sqrt(v[3 + i]) : 0;
                    if (v[i] != 0 && pole_nm >= first_nm && pole_nm <= last_nm)
                        fail(line, what + ": the formula has a pole at " + format_g9(pole_nm) + " nm (B" +
                                       std::to_string(i + 1) + " = " + num(v[i]) + ", C" + std::to_string(i + 1) +
                                       " = " + num(v[3 + i]) + " square micrometres), inside the " + num(first_nm) +
                                       " to " + num(last_nm) + " nm a stack tabulates: its index is unbounded there");
                }
                formula = [f](double nm) { return f.n(nm); };
            } else {
                Cauchy f{v[0], v[1], v.size() > 2 ? v[2] : 0.0};
                formula = [f](double nm) { return f.n(nm); };
            }
            std::string list;
            for (double x : v) list += (list.empty() ? "" : ", ") + num(float(x));
            given = std::string("{ ") + (sellmeier ? "sellmeier" : "cauchy") + " = [" + list + "] }";
        }
        SpectralTable t;
        t.file = what;
        t.columns = {"value"};
        t.values.resize(1);
        for (double nm = first_nm; nm <= last_nm; nm += 2) {
            const double v = formula(nm);
            if (!key.admits(v))
                fail(line, what + ": " + key.name + " must be in " + key.range_text() + " (" + key.meaning +
                               "), the formula gives " + written_value_text(v) + " at " + num(nm) + " nm");
            t.wavelength_nm.push_back(nm);
            t.values[0].push_back(v);
        }
        return spectral_value(std::move(t), key, y, what, line, given);
    }

    // A key's spectrum into the layer (given: its TOML where it was a name or a formula), and its RGB value: the
    // sRGB primaries' dominant wavelengths, which it must cover, or, for a key of one value (a dielectric's IOR), the
    // d line.
    glm::vec3 spectral_value(SpectralTable t, const LayerKey& key, Layer& y, const std::string& what, int line,
                             const std::string& given) const {
        glm::vec3 rgb;
        if (key.one_value) {   // dispersion: one value in every channel, at the d line (a glass's n_d)
            if (kDispersionRgbNm < t.first_nm() || kDispersionRgbNm > t.last_nm())
                fail(line, what + ": the spectrum covers " + num(float(t.first_nm())) + " to " +
                               num(float(t.last_nm())) + " nm; it must cover " + num(float(kDispersionRgbNm)) +
                               " nm (the d line), where an RGB run reads it: one IOR in every channel");
            rgb = glm::vec3(float(t.at(0, kDispersionRgbNm)));
            y.spectra.push_back({key.name, std::move(t), rgb, given});
            return rgb;
        }
        for (int c = 0; c < kChannels; ++c) {
            const double nm = srgb_dominant_wavelengths()[size_t(c)];
            if (nm < t.first_nm() || nm > t.last_nm()) {
                // to 0.01 nm outward, so that a spectrum written with the ends quoted covers them
                char need[64];
                std::snprintf(need, sizeof need, "%.2f to %.2f nm",
                              std::floor(srgb_dominant_wavelengths()[2] * 100) / 100,
                              std::ceil(srgb_dominant_wavelengths()[0] * 100) / 100);
                fail(line, what + ": the spectrum covers " + num(float(t.first_nm())) + " to " +
                               num(float(t.last_nm())) + " nm; it must cover at least " + need +
                               ", where an RGB run reads it (the sRGB primaries' dominant wavelengths)");
            }
            rgb[c] = float(t.at(0, nm));
        }
        y.spectra.push_back({key.name, std::move(t), rgb, given});
        return rgb;
    }

    // A conductor's `material` (NamedKey): a measured one, its n and k reduced to RGB (measured_materials.h); not
    // with the keys it gives.
    void material(const NamedKey& n, const toml::node& m, const toml::table& t, Layer& y, int line,
                  const std::string& pre) const {
        if (!m.is_string())
            fail(line, pre + "material must be a string naming a measured conductor (" + measured_conductor_names() +
                           "), got " + type_name(m));
        const std::string name = m.as_string()->get();
        const MeasuredConductor* c = find_measured_conductor(name);
        if (!c) fail(line, pre + "unknown material '" + name + "'; known materials: " + measured_conductor_names());
        for (const char* key : n.gives)
            if (t.contains(key))
                fail(line_of(*t.get(key), line), pre + "give either material or ior and k, not both (material '" +
                                                     name + "' gives n and k from " + c->reference + ")");
        const ConductorRgb rgb = conductor_rgb(*c);
        y.*n.value = name;
        y.ior = glm::vec3(float(rgb.n[0]), float(rgb.n[1]), float(rgb.n[2]));
        y.k = glm::vec3(float(rgb.k[0]), float(rgb.k[1]), float(rgb.k[2]));
    }

    // A word key's value (ChoiceKey): one of its words, as a string.
    void choice(const ChoiceKey& c, const toml::node& v, Layer& y, int line, const std::string& pre) const {
        const std::string* w = v.is_string() ? &v.as_string()->get() : nullptr;
        for (int i = 0; w && i < c.word_count(); ++i)
            if (*w == c.words[size_t(i)]) return c.set(y, i);
        fail(line, pre + c.name + " must be " + c.words_text() + " (" + c.meaning + "), got " +
                       (w ? "\"" + *w + "\"" : type_name(v)));
    }

    Layer layer(const toml::table& t, size_t i, int fallback, LayerLines& ll) const {
        Layer y;
        const int tl = table_line(t, fallback);
        ll = LayerLines(tl);
        y.line = tl;
        const std::string pre = "layer " + std::to_string(i + 1) + ": ";
        y.kind = kind_of(t, tl, pre);
        only_keys_of(t, y.kind, tl, pre);
        const NamedKey* named = nullptr;   // a name given for keys of the layer (their lines: the name's)
        int named_line = tl;
        for (const NamedKey& n : named_keys())
            if (const toml::node* m = n.kind == y.kind ? t.get(n.name) : nullptr) {
                named = &n;
                named_line = line_of(*m, tl);
                material(n, *m, t, y, named_line, pre);
            }
        for (const LayerKey* key : keys_of(y.kind)) {
            if (named && named->gives_key(key->name))
                ll.of(*key) = named_line;
            else
                read_key(t, *key, y, tl, ll.of(*key), pre);
        }
        for (const ChoiceKey& c : choice_keys())
            if (const toml::node* v = c.of_kind(y.kind) ? t.get(c.name) : nullptr)
                choice(c, *v, y, line_of(*v, tl), pre);
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
            if (!is_top_key(k))
                fail(line_of(key, node),
                     "unknown key '" + std::string(k) + "'; allowed top-level keys: " + top_key_names());
        }

        const toml::node* name = t.get("name");
        if (!name) fail(1, "missing required key 'name' (the stack's name, a non-empty string)");
        L.name = line_of(*name, 1);
        if (!name->is_string()) fail(L.name, std::string("name must be a string, got ") + type_name(*name));
        s.name = name->as_string()->get();
        refuse_control_characters("name", s.name, L.name);

        if (const toml::node* d = t.get("description")) {
            if (!d->is_string())
                fail(line_of(*d, 1), std::string("description must be a string, got ") + type_name(*d));
            s.description = d->as_string()->get();
            refuse_control_characters("description", s.description, line_of(*d, 1));
        }

        if (const toml::node* e = t.get("exterior_ior")) {
            L.exterior = line_of(*e, 1);
            if (e->is_array())
                fail(L.exterior,
                     "exterior_ior must be a single number > 0 (the medium above the stack is one dielectric, "
                     "the same for all channels), got an array");
            const double v = number(*e, "exterior_ior", L.exterior);
            const StackKey& k = *find_stack_key("exterior_ior");
            if (!k.admits(v))
                fail(L.exterior, std::string("exterior_ior must be in ") + k.range_text() + " (" + k.meaning +
                                     "), got " + written_value_text(v));
            s.exterior_ior = float(v);
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
    return parse_stack_string(read_input_file(path, "stack file"), path);
}

void validate_stack(const Stack& s) {
    StackLines L;
    for (const Layer& y : s.layers) L.layers.emplace_back(y.line);
    check(s, L);
}

bool layer_key_applies(InterfaceKind kind, const std::string& key) { return find_layer_key(kind, key) != nullptr; }

namespace {

// What a dielectric interface and the medium under it do: transmittance, scattering, eta and total internal reflection.
void describe_dielectric(std::ostringstream& o, const Stack& s, size_t i) {
    const Layer& y = s.layers[i];
    const float nb = y.ior.x, na = s.ior_above(i).x;
    if (i + 1 == s.layers.size()) {
        o << "      below: semi-infinite substrate\n";
    } else {
        o << "      medium below: transmittance at normal incidence " << rgb_fixed(glm::exp(-y.optical_depth), 3)
          << "\n";
        if (s.medium_scatters(i))
            o << "      scattering: scattering optical depth " << derived(y.optical_depth * y.scattering_albedo)
              << ", absorption " << derived(y.optical_depth * (glm::vec3(1.0f) - y.scattering_albedo))
              << (y.phase == MediumPhase::Hg
                      ? ", Henyey-Greenstein g " + num(y.phase_g)
                      : ", SGGX specular " +
                            std::string(y.phase == MediumPhase::SggxFibre ? "fibres along the normal"
                                                                          : "flakes facing the normal") +
                            ", alpha " + num(y.fibre_roughness) + " (sigma " +
                            num(y.fibre_roughness * y.fibre_roughness) + ")")
              << "\n";
        else if (y.scattering_albedo != glm::vec3(0) || y.phase_g != 0.0f)
            o << "      scattering_albedo and phase_g: no effect (nothing scatters where the optical depth or the "
                 "albedo is 0)\n";
    }
    o << "      eta = n_below/n_above = " << num(nb) << "/" << num(na) << " = " << fixed(nb / na, 4);
    const double deg = 180.0 / std::numbers::pi;
    if (nb > na)
        o << "; total internal reflection for light arriving from below beyond the critical angle "
          << fixed(float(std::asin(na / nb) * deg), 2) << " deg\n";
    else if (nb < na)
        o << "; total internal reflection for light arriving from above beyond the critical angle "
          << fixed(float(std::asin(nb / na) * deg), 2) << " deg\n";
    else
        o << "; index-matched: no refraction, no total internal reflection\n";
}

}   // namespace

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
        o << "  layer " << i + 1;
        if (y.line > 0) o << " (line " << y.line << ")";
        o << ": " << to_string(y.kind) << (kind_info(y.kind).opaque ? " base" : " interface");
        const char* sep = ": ";
        const bool substrate = i + 1 == s.layers.size() && !kind_info(y.kind).opaque;
        for (const LayerKey* key : keys_of(y.kind)) {   // every key of its kind, as the vocabulary has them
            if (key->medium && substrate) continue;
            if (!key_of_layer_phase(*key, y)) continue;   // Henyey-Greenstein's g, or the microflakes' alpha
            o << sep << key->name << " " << rgb(key->get(y));
            sep = ", ";
        }
        if (find_layer_key(y.kind, "roughness") && y.roughness == 0.0f) o << " (a perfectly smooth interface)";
        for (const ChoiceKey& c : choice_keys())
            if (c.of_kind(y.kind) && c.get(y) != 0 && !c.medium)
                o << ", " << c.name << " " << c.words[size_t(c.get(y))] << (y.roughness == 0.0f ? " (no effect)" : "");
        o << "\n";
        if (y.kind == InterfaceKind::Dielectric) describe_dielectric(o, s, i);
        for (const KeySpectrum& sp : y.spectra)
            if (y.intact_spectrum(sp.key, find_layer_key(y.kind, sp.key)->get(y)))
                o << "      " << sp.key << (sp.given.empty() ? "" : " = " + sp.given) << ": a spectrum of "
                  << sp.table.wavelength_nm.size() << " points, " << num(float(sp.table.first_nm())) << " to "
                  << num(float(sp.table.last_nm())) << " nm; in RGB, "
                  << (find_layer_key(y.kind, sp.key)->one_value
                          ? "its value at 587.56 nm (the d line) in every channel: it disperses, and a spectral run "
                            "traces one wavelength per pass"
                          : "its values at the sRGB primaries' dominant wavelengths")
                  << "\n";
        if (!y.material.empty())
            o << "      material " << y.material << " (" << find_measured_conductor(y.material)->reference
              << "): in RGB, " << kConductorRgbReduction << "\n";
        if (y.kind == InterfaceKind::Conductor)
            o << "      eta = (n + i k)/n_above = " << rgb_fixed(y.ior / s.ior_above(i).x, 4) << " + i "
              << rgb_fixed(y.k / s.ior_above(i).x, 4) << "\n";
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
        const bool medium = i + 1 < s.layers.size();   // a layer over another has a medium under its interface
        // a measured material as its name, a spectrum as its pairs, unless changed since (a sweep's or a fit's value)
        const NamedKey* named = nullptr;
        for (const NamedKey& n : named_keys())
            if (n.kind == y.kind && y.material_intact()) named = &n;
        if (named) o << named->name << " = " << toml_string(y.*named->value) << "\n";
        for (const LayerKey* key : keys_of(y.kind)) {
            if (named && named->gives_key(key->name)) continue;
            const glm::vec3 v = key->get(y);
            if (const KeySpectrum* sp = y.intact_spectrum(key->name, v); sp && !sp->given.empty()) {
                o << key->name << " = " << sp->given << "\n";
                continue;
            }
            if (const KeySpectrum* sp = y.intact_spectrum(key->name, v)) {
                o << key->name << " = [";
                for (size_t j = 0; j < sp->table.wavelength_nm.size(); ++j)
                    o << (j ? ", [" : "[") << num(float(sp->table.wavelength_nm[j])) << ", "
                      << num(float(sp->table.values[0][j])) << "]";
                o << "]\n";
                continue;
            }
            if (!key->medium || v != glm::vec3(key->fallback) || (key->always_on_medium && medium))
                o << key->name << " = " << rgb(v) << "\n";
        }
        for (const ChoiceKey& c : choice_keys())   // a word only where it is not the default
            if (c.of_kind(y.kind) && c.get(y) != 0) o << c.name << " = \"" << c.words[size_t(c.get(y))] << "\"\n";
    }
    return o.str();
}

}   // namespace gonio
