// stack_vocabulary.h: the words of a stack file, written once. One table of interface kinds and one of layer keys
// (per kind: name, shape, valid range, default, unit, meaning, where a Layer keeps it), read by the parser and the
// writer (stack.cpp), `gonio check`, sweeps' [[vary]], the viewer's controls and --set, random stacks' coverage test
// and stacks/README.md's key table (tests/test_stack.cpp compares the two). The shaders' KIND_* and MAX_LAYERS
// (stack_params.glsl) are tied to InterfaceKind and kMaxLayers by static_asserts (stack_vocabulary.cpp).
//
// A new interface kind is a row of interface_kinds() and its rows of layer_keys(); one without keys is refused when
// the tables are first read (check_vocabulary), and the shaders' kind switches answer NaN for a kind they lack.
#pragma once
#include "stack.h"

#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gonio {

struct KindInfo {
    InterfaceKind kind;
    const char* name;   // its word in a stack file (interface = "...")
    bool opaque;   // an opaque base: it must be the last layer
    const char* doc;   // one line
};
std::span<const KindInfo> interface_kinds();
const KindInfo& kind_info(InterfaceKind k);
const KindInfo* find_kind(std::string_view name);   // nullptr: no such kind
std::string kind_names();   // "dielectric, conductor, lambertian"

// A key's value: one number, or a number (the same in every channel) or an array of 3 (R, G, B).
enum class KeyShape { Number, Rgb };

// A key of a [[layer]] of one kind (the same name may be a key of several kinds, with other ranges).
struct LayerKey {
    const char* name;
    InterfaceKind kind;
    KeyShape shape;
    ParameterRange range;   // valid values; see open and or_zero
    bool open = false;   // the open interval (lo, hi)
    bool or_zero = false;   // 0 is valid too (roughness: a smooth interface)
    bool required = false;
    bool medium = false;   // of the medium under the interface: absent on a transmissive stack's last layer
    bool always_on_medium = false;   // written by stack_to_toml on every layer with a medium, even at its fallback
    bool one_value = false;   // an Rgb key that must be the same in every channel (given as an array, refused)
    float fallback = 0.0f;   // its value when absent
    const char* unit;   // "1" for a pure number
    const char* meaning;   // what it is, in the refusals and the docs
    float Layer::*number = nullptr;   // where a Layer keeps it (one of the two)
    glm::vec3 Layer::*rgb = nullptr;
    ParameterRange typical{0.0f, 0.0f};   // the viewer's controls span this ([0, 0]: range)

    glm::vec3 get(const Layer& y) const { return number ? glm::vec3(y.*number) : y.*rgb; }
    void set(Layer& y, glm::vec3 v) const {
        if (number)
            y.*number = v.x;
        else
            y.*rgb = v;
    }
    // "[1, 10]", "(-1, 1)", "[1e-04, 1] or 0"
    std::string range_text() const;
    // Whether v is valid as written (a double) and as a Layer keeps it (a float, where 0.99999999 is 1)
    bool admits(double v) const;
};

// Every (kind, key), grouped by kind in interface_kinds()'s order, each kind's keys in the order a layer is written.
std::span<const LayerKey> layer_keys();
std::vector<const LayerKey*> keys_of(InterfaceKind k);
const LayerKey* find_layer_key(InterfaceKind k, std::string_view name);   // nullptr: not a key of that kind
// Every distinct key name of any kind, in table order ("roughness, ior, k, ..."; "interface" not included).
std::vector<std::string> layer_key_names();
bool is_layer_key(std::string_view name);
// Whether a medium key belongs to the layer's phase function: phase_g to Henyey-Greenstein's, fibre_roughness to
// microflakes' (the other's is refused: stack.cpp check_phase); every other key does. `gonio check` and the viewer
// show a layer's keys by it.
bool key_of_layer_phase(const LayerKey& key, const Layer& y);

// The stack's own numeric keys besides its layers (exterior_ior), for sweeps and the viewer.
struct StackKey {
    const char* name;
    ParameterRange range;
    float fallback;   // its value when absent
    float Stack::*value;
    const char* meaning;
    bool admits(double v) const;   // in the closed range as written and as a float
    std::string range_text() const;   // "[1, 10]"
};
std::span<const StackKey> stack_keys();
const StackKey* find_stack_key(std::string_view name);

// The stack's own keys that are not numbers (exterior_ior is a StackKey): its name, description and layers, in the
// order a stack file is written.
struct TextKey {
    const char* name;
    bool required;
    const char* value;   // what it takes, in refusals and the docs
    const char* meaning;
};
std::string top_key_names();   // "name, description, exterior_ior, layer": every top-level key
bool is_top_key(std::string_view name);

// A layer key whose value is a name that gives other keys' values instead of them: a conductor's `material`, a
// measured conductor whose n and k it gives (host/spectral/measured_materials.h).
struct NamedKey {
    const char* name;
    InterfaceKind kind;
    std::array<const char*, 2> gives;   // the keys it gives, which may not be given beside it
    std::string Layer::*value;   // where a Layer keeps the name
    const char* meaning;
    std::string (*names)();   // the names it takes, "Ag, Al, ..."
    bool gives_key(std::string_view key) const { return std::find(gives.begin(), gives.end(), key) != gives.end(); }
};
std::span<const NamedKey> named_keys();

// A layer key whose value is one word of a few: a rough interface's microsurface, `distribution`, `shadowing` and
// `microfacets` (shaders/lib/microsurface.glsl), and a medium's `phase` (shaders/lib/medium.glsl). words[0] is the
// default, which stack_to_toml leaves unwritten (today's files).
struct ChoiceKey {
    const char* name;
    std::array<InterfaceKind, 2> kinds;   // the kinds it is a key of
    std::array<const char*, 3> words;   // nullptr after the last
    int (*get)(const Layer&);   // the index of the layer's word
    void (*set)(Layer&, int);
    const char* meaning;
    bool medium = false;   // of the medium under the interface (else of the rough interface's microsurface)
    bool of_kind(InterfaceKind k) const { return std::find(kinds.begin(), kinds.end(), k) != kinds.end(); }
    int word_count() const { return words[2] ? 3 : 2; }
    std::string words_text() const;   // "\"ggx\" or \"beckmann\""
};
std::span<const ChoiceKey> choice_keys();
const ChoiceKey* find_choice_key(std::string_view name);

// A value as written and, where a float holds it otherwise, as a float: "1.00000001", "0.99999999 (1 as a 32-bit
// float)"; what a refusal quotes
std::string written_value_text(double v);

// Every key (top level, layers' numbers, names) as a Markdown table (stacks/README.md holds it; tests/test_stack.cpp
// checks that it is this one).
std::string keys_markdown_table();

}   // namespace gonio
