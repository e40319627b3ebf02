// stack_vocabulary.cpp: the tables of stack_vocabulary.h, and their ties to the shaders' constants.
#include "stack_vocabulary.h"
#include "glasses.h"
#include "measured_materials.h"
#include "stack_params.glsl"   // KIND_*, MAX_LAYERS
#include "text_format.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace gonio {

static_assert(kMaxLayers == MAX_LAYERS, "host/core/stack.h kMaxLayers and stack_params.glsl MAX_LAYERS");
static_assert(kChannels == int(CHANNELS), "host/core/stack.h kChannels and stack_params.glsl CHANNELS");
static_assert(uint(InterfaceKind::Dielectric) == KIND_DIELECTRIC && uint(InterfaceKind::Conductor) == KIND_CONDUCTOR &&
                  uint(InterfaceKind::Lambertian) == KIND_LAMBERTIAN,
              "InterfaceKind and stack_params.glsl KIND_*");

namespace {

constexpr KindInfo kKinds[] = {
    {InterfaceKind::Dielectric, "dielectric", false,
     "a dielectric interface and the medium under it; as the last layer, the interface onto a transmissive "
     "stack's substrate"},
    {InterfaceKind::Conductor, "conductor", true, "an opaque conductor base (complex IOR)"},
    {InterfaceKind::Lambertian, "lambertian", true, "an opaque Lambertian base"},
};
static_assert(std::size(kKinds) == KIND_LAMBERTIAN + 1, "a row of kKinds per KIND_* of stack_params.glsl");

constexpr const char* kRoughnessMeaning =
    "the microfacets' alpha (GGX or Beckmann: `distribution`); 0 is a smooth interface, below 1e-4 the lobe is "
    "narrower than float precision resolves";

const LayerKey kKeys[] = {
    {.name = "roughness",
     .kind = InterfaceKind::Dielectric,
     .shape = KeyShape::Number,
     .range = kRoughnessRange,
     .or_zero = true,
     .unit = "1",
     .meaning = kRoughnessMeaning,
     .number = &Layer::roughness},
    {.name = "ior",
     .kind = InterfaceKind::Dielectric,
     .shape = KeyShape::Rgb,
     .range = kDielectricIorRange,
     .required = true,
     .one_value = true,
     .unit = "1",
     .meaning = "absolute IOR of the medium under the interface",
     .rgb = &Layer::ior,
     .typical = {1.0f, 4.0f}},
    {.name = "optical_depth",
     .kind = InterfaceKind::Dielectric,
     .shape = KeyShape::Rgb,
     .range = kOpticalDepthRange,
     .medium = true,
     .always_on_medium = true,
     .unit = "1",
     .meaning = "extinction optical depth tau = sigma_t * d",
     .rgb = &Layer::optical_depth,
     .typical = {0.0f, 50.0f}},
    {.name = "scattering_albedo",
     .kind = InterfaceKind::Dielectric,
     .shape = KeyShape::Rgb,
     .range = kAlbedoRange,
     .medium = true,
     .unit = "1",
     .meaning = "single-scattering albedo sigma_s / sigma_t; above 1 a medium would create light",
     .rgb = &Layer::scattering_albedo},
    {.name = "phase_g",
     .kind = InterfaceKind::Dielectric,
     .shape = KeyShape::Number,
     .range = kPhaseGRange,
     .open = true,
     .medium = true,
     .unit = "1",
     .meaning = "Henyey-Greenstein asymmetry: 0 isotropic, > 0 forward; at +-1 the phase function is a delta",
     .number = &Layer::phase_g,
     .typical = {-0.99f, 0.99f}},
    {.name = "fibre_roughness",
     .kind = InterfaceKind::Dielectric,
     .shape = KeyShape::Number,
     .range = kFibreRoughnessRange,
     .or_zero = true,
     .medium = true,
     .unit = "1",
     .meaning = "a microflake medium's roughness alpha (sigma = alpha^2, the fibres' cross-section as the sheen "
                "authors set it); 0 where the phase is \"hg\"",
     .number = &Layer::fibre_roughness},
    {.name = "roughness",
     .kind = InterfaceKind::Conductor,
     .shape = KeyShape::Number,
     .range = kRoughnessRange,
     .or_zero = true,
     .unit = "1",
     .meaning = kRoughnessMeaning,
     .number = &Layer::roughness},
    {.name = "ior",
     .kind = InterfaceKind::Conductor,
     .shape = KeyShape::Rgb,
     .range = kConductorIorRange,
     .required = true,
     .unit = "1",
     .meaning = "real part of the conductor's complex IOR",
     .rgb = &Layer::ior,
     .typical = {0.01f, 10.0f}},
    {.name = "k",
     .kind = InterfaceKind::Conductor,
     .shape = KeyShape::Rgb,
     .range = kConductorKRange,
     .required = true,
     .unit = "1",
     .meaning = "extinction coefficient, imaginary part of the complex IOR",
     .rgb = &Layer::k,
     .typical = {0.0f, 20.0f}},
    {.name = "albedo",
     .kind = InterfaceKind::Lambertian,
     .shape = KeyShape::Rgb,
     .range = kAlbedoRange,
     .required = true,
     .unit = "1",
     .meaning = "diffuse albedo; above 1 it would reflect more light than it receives: non-physical, nothing is "
                "clamped",
     .rgb = &Layer::albedo},
};

const StackKey kStackKeys[] = {
    {"exterior_ior", kExteriorIorRange, 1.0f, &Stack::exterior_ior,
     "absolute IOR of the medium above the stack, 1 for air"},
};

const TextKey kTextKeys[] = {
    {"name", true, "a string", "the stack's name, in file names and outputs; no control character"},
    {"description", false, "a string", "one line on what the stack is"},
    {"layer", true, "[[layer]] sections", "the layers, top to bottom, each an interface kind and its keys"},
};

const NamedKey kNamedKeys[] = {
    {"material",
     InterfaceKind::Conductor,
     {"ior", "k"},
     &Layer::material,
     "a measured conductor: its n and k from the measurement, reduced to RGB (an RGB run) or read per band (a "
     "spectral run); instead of ior and k",
     &measured_conductor_names},
};

// Every kind has keys, every key a kind of the table and one place in Layer: checked once, when first read.
bool check_vocabulary() {
    for (const KindInfo& k : kKinds)
        if (std::none_of(std::begin(kKeys), std::end(kKeys), [&](const LayerKey& y) { return y.kind == k.kind; }))
            throw std::logic_error(std::string("stack vocabulary: interface kind ") + k.name + " has no keys");
    for (const LayerKey& y : kKeys)
        if ((y.number == nullptr) == (y.rgb == nullptr) || (y.shape == KeyShape::Number) != (y.number != nullptr))
            throw std::logic_error(std::string("stack vocabulary: key ") + y.name + " has no single place in Layer");
    return true;
}

const ChoiceKey kChoiceKeys[] = {
    {.name = "distribution",
     .kinds = {InterfaceKind::Dielectric, InterfaceKind::Conductor},
     .words = {"ggx", "beckmann"},
     .get = [](const Layer& y) { return int(y.distribution); },
     .set = [](Layer& y, int i) { y.distribution = MicrofacetDistribution(i); },
     .meaning = "the rough interface's microfacet distribution: GGX (Trowbridge-Reitz) or Beckmann; alpha is its "
                "roughness either way (no effect where roughness is 0)"},
    {.name = "shadowing",
     .kinds = {InterfaceKind::Dielectric, InterfaceKind::Conductor},
     .words = {"height-correlated", "separable"},
     .get = [](const Layer& y) { return int(y.shadowing); },
     .set = [](Layer& y, int i) { y.shadowing = Shadowing(i); },
     .meaning = "the rough interface's Smith masking-shadowing: height-correlated G2 = 1 / (1 + L(wi) + L(wo)) or "
                "separable G1(wi) G1(wo) (no effect where roughness is 0)"},
    {.name = "microfacets",
     .kinds = {InterfaceKind::Dielectric, InterfaceKind::Conductor},
     .words = {"single", "multiple"},
     .get = [](const Layer& y) { return int(y.microfacets); },
     .set = [](Layer& y, int i) { y.microfacets = Microfacets(i); },
     .meaning = "light on the rough interface's microsurface: scattered once (what leaves towards another microfacet "
                "is lost) or walking on it until it leaves (Heitz et al. 2016; height-correlated by construction, so "
                "not with separable shadowing; no effect where roughness is 0)"},
    {.name = "phase",
     .kinds = {InterfaceKind::Dielectric, InterfaceKind::Dielectric},
     .words = {"hg", "sggx-fibre", "sggx-flake"},
     .get = [](const Layer& y) { return int(y.phase); },
     .set = [](Layer& y, int i) { y.phase = MediumPhase(i); },
     .meaning = "the medium's phase function: Henyey-Greenstein (phase_g), or specular SGGX microflakes (Heitz et al. "
                "2015), fibres along the normal or flakes facing it, of roughness fibre_roughness, whose projected "
                "area scales the extinction in each direction",
     .medium = true},
};

}   // namespace

std::span<const ChoiceKey> choice_keys() { return kChoiceKeys; }

const ChoiceKey* find_choice_key(std::string_view name) {
    for (const ChoiceKey& k : kChoiceKeys)
        if (name == k.name) return &k;
    return nullptr;
}

std::string ChoiceKey::words_text() const {
    std::string t;
    for (int i = 0; i < word_count(); ++i)
        t += std::string(i == 0 ? "" : (i + 1 == word_count() ? " or " : ", ")) + "\"" + words[size_t(i)] + "\"";
    return t;
}

std::span<const KindInfo> interface_kinds() { return kKinds; }

const KindInfo& kind_info(InterfaceKind k) {
    for (const KindInfo& i : kKinds)
        if (i.kind == k) return i;
    throw std::logic_error("invalid interface kind " + std::to_string(int(k)));
}

const KindInfo* find_kind(std::string_view name) {
    for (const KindInfo& i : kKinds)
        if (name == i.name) return &i;
    return nullptr;
}

std::string kind_names() {
    std::string s;
    for (const KindInfo& i : kKinds) s += (s.empty() ? "" : ", ") + std::string(i.name);
    return s;
}

std::span<const LayerKey> layer_keys() {
    static const bool checked = check_vocabulary();
    (void)checked;
    return kKeys;
}

std::vector<const LayerKey*> keys_of(InterfaceKind k) {
    std::vector<const LayerKey*> out;
    for (const LayerKey& y : layer_keys())
        if (y.kind == k) out.push_back(&y);
    return out;
}

const LayerKey* find_layer_key(InterfaceKind k, std::string_view name) {
    for (const LayerKey& y : layer_keys())
        if (y.kind == k && name == y.name) return &y;
    return nullptr;
}

std::vector<std::string> layer_key_names() {
    std::vector<std::string> out;
    for (const LayerKey& y : layer_keys())
        if (std::find(out.begin(), out.end(), y.name) == out.end()) out.push_back(y.name);
    return out;
}

bool key_of_layer_phase(const LayerKey& key, const Layer& y) {
    if (key.number == &Layer::phase_g) return y.phase == MediumPhase::Hg;
    if (key.number == &Layer::fibre_roughness) return y.phase != MediumPhase::Hg;
    return true;
}

bool is_layer_key(std::string_view name) {
    return std::any_of(layer_keys().begin(), layer_keys().end(), [&](const LayerKey& y) { return name == y.name; });
}

std::string LayerKey::range_text() const {
    std::string s =
        (open ? "(" : "[") + format_shortest(range.lo) + ", " + format_shortest(range.hi) + (open ? ")" : "]");
    return or_zero ? s + " or 0" : s;
}

bool LayerKey::admits(double v) const {
    auto in = [&](double x) {
        return (or_zero && x == 0) || (open ? x > range.lo && x < range.hi : x >= range.lo && x <= range.hi);
    };
    return std::isfinite(v) && in(v) && in(double(float(v)));
}

bool StackKey::admits(double v) const {
    auto in = [&](double x) { return x >= range.lo && x <= range.hi; };
    return std::isfinite(v) && in(v) && in(double(float(v)));
}

std::string StackKey::range_text() const {
    return "[" + format_shortest(range.lo) + ", " + format_shortest(range.hi) + "]";
}

std::string written_value_text(double v) {
    char b[40];
    auto r = std::to_chars(b, b + sizeof b, v);
    std::string t(b, r.ptr);
    if (std::isfinite(v) && double(float(v)) != v && format_shortest(float(v)) != t)
        t += " (" + format_shortest(float(v)) + " as a 32-bit float)";
    return t;
}

std::span<const StackKey> stack_keys() { return kStackKeys; }

std::string top_key_names() {
    std::string s = std::string(kTextKeys[0].name) + ", " + kTextKeys[1].name;
    for (const StackKey& k : kStackKeys) s += std::string(", ") + k.name;
    for (size_t i = 2; i < std::size(kTextKeys); ++i) s += std::string(", ") + kTextKeys[i].name;
    return s;
}

bool is_top_key(std::string_view name) {
    return find_stack_key(name) ||
           std::any_of(std::begin(kTextKeys), std::end(kTextKeys), [&](const TextKey& k) { return name == k.name; });
}

std::span<const NamedKey> named_keys() { return kNamedKeys; }

const StackKey* find_stack_key(std::string_view name) {
    for (const StackKey& k : kStackKeys)
        if (name == k.name) return &k;
    return nullptr;
}

std::string keys_markdown_table() {
    std::string t = "| kind | key | value | valid range | default | meaning |\n|---|---|---|---|---|---|\n";
    auto text_row = [&](const TextKey& k) {
        t += std::string("| (top level) | `") + k.name + "` | " + k.value + " | | " +
             (k.required ? "required" : "none") + " | " + k.meaning + " |\n";
    };
    text_row(kTextKeys[0]);
    text_row(kTextKeys[1]);
    for (const StackKey& k : stack_keys())
        t += std::string("| (top level) | `") + k.name + "` | one number | " + k.range_text() + " | " +
             format_shortest(k.fallback) + " | " + k.meaning + " |\n";
    for (size_t i = 2; i < std::size(kTextKeys); ++i) text_row(kTextKeys[i]);
    for (const KindInfo& kind : interface_kinds()) {   // each kind's numbers, then its names
        std::string given_by;   // " (or `material`)" where a name of the kind gives the key
        for (const LayerKey* y : keys_of(kind.kind)) {
            const std::string value =
                y->shape == KeyShape::Number ? "one number"
                : y->one_value ? "one number; or, dispersive, a spectrum, a named glass (" + named_glass_names() +
                                     ") or a formula ({ sellmeier = [...] }, { cauchy = [...] })"
                               : std::string("a number, [R, G, B] or a spectrum [[nm, value], ...]");
            given_by.clear();
            for (const NamedKey& n : named_keys())
                if (n.kind == kind.kind && n.gives_key(y->name)) given_by = std::string(" (or `") + n.name + "`)";
            const std::string fallback = y->required ? "required" + given_by : format_shortest(y->fallback);
            t += std::string("| ") + kind.name + " | `" + y->name + "` | " + value + " | " + y->range_text() + " | " +
                 fallback + " | " + y->meaning +
                 (y->medium ? " (of the medium under the interface: not on a transmissive stack's last layer)" : "") +
                 " |\n";
        }
        for (const NamedKey& n : named_keys())
            if (n.kind == kind.kind)
                t += std::string("| ") + kind.name + " | `" + n.name + "` | a name | " + n.names() + " | none | " +
                     n.meaning + " |\n";
        for (const ChoiceKey& c : choice_keys())
            if (c.of_kind(kind.kind))
                t += std::string("| ") + kind.name + " | `" + c.name + "` | a word | " + c.words_text() + " | " +
                     c.words[0] + " | " + c.meaning + " |\n";
    }
    return t;
}

}   // namespace gonio
