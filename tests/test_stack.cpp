// Stack files: shipped stacks parse and round-trip, malformed ones are refused with file:line: messages.
#include "stack.h"
#include "stack_vocabulary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

namespace fs = std::filesystem;
using namespace gonio;

namespace {

const fs::path kRoot = GONIO_SOURCE_DIR;

std::vector<fs::path> toml_files(const fs::path& dir) {
    std::vector<fs::path> v;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().extension() == ".toml") v.push_back(e.path());
    std::sort(v.begin(), v.end());
    return v;
}

void expect_same_values(const Stack& a, const Stack& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.description, b.description);
    EXPECT_EQ(a.exterior_ior, b.exterior_ior);
    ASSERT_EQ(a.layers.size(), b.layers.size());
    for (size_t i = 0; i < a.layers.size(); ++i) {
        SCOPED_TRACE("layer " + std::to_string(i + 1));
        const Layer &x = a.layers[i], &y = b.layers[i];
        EXPECT_EQ(x.kind, y.kind);
        EXPECT_EQ(x.roughness, y.roughness);
        EXPECT_EQ(x.ior, y.ior);
        EXPECT_EQ(x.k, y.k);
        EXPECT_EQ(x.optical_depth, y.optical_depth);
        EXPECT_EQ(x.albedo, y.albedo);
    }
}

// Returns the message of the StackError thrown by f, or fails.
template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const StackError& e) { return e.what(); }
    ADD_FAILURE() << "no StackError thrown";
    return "";
}

const char* kTwoLayers = R"(name = "t"
[[layer]]
interface = "dielectric"
ior = 1.5

[[layer]]
interface = "lambertian"
albedo = 0.25
)";

}   // namespace

TEST(ShippedStacks, ParseValidateRoundTrip) {
    const auto files = toml_files(kRoot / "stacks");
    EXPECT_GE(files.size(), 4u);
    for (const auto& f : files) {
        SCOPED_TRACE(f.string());
        Stack s;
        ASSERT_NO_THROW(s = parse_stack_file(f.string()));
        EXPECT_EQ(s.name, f.stem().string());
        EXPECT_FALSE(s.description.empty());
        EXPECT_EQ(s.source_path, f.string());
        EXPECT_FALSE(s.source_text.empty());
        EXPECT_NO_THROW(validate_stack(s));
        EXPECT_NE(describe_stack(s).find(s.name), std::string::npos);
        const std::string text = stack_to_toml(s);
        Stack back;
        ASSERT_NO_THROW(back = parse_stack_string(text, "roundtrip.toml")) << text;
        expect_same_values(s, back);
        EXPECT_EQ(stack_to_toml(back), text);
    }
}

TEST(ShippedStacks, PaperParameters) {
    auto load = [](const char* n) { return parse_stack_file((kRoot / "stacks" / n).string()); };
    const Stack plastic = load("plastic.toml"), paint = load("metallic-paint.toml"),
                frosted = load("frosted-metal.toml"), slab = load("transparent-slab.toml");
    for (const Stack* s : {&plastic, &paint, &frosted, &slab}) {
        ASSERT_EQ(s->layers.size(), 2u);
        EXPECT_EQ(s->layers[0].kind, InterfaceKind::Dielectric);
        EXPECT_EQ(s->layers[0].ior, glm::vec3(1.5f));
        EXPECT_EQ(s->exterior_ior, 1.0f);
    }
    EXPECT_EQ(plastic.layers[0].roughness, 0.05f);
    EXPECT_EQ(plastic.base().kind, InterfaceKind::Lambertian);
    EXPECT_EQ(paint.layers[0].roughness, 0.001f);
    EXPECT_EQ(paint.base().kind, InterfaceKind::Conductor);
    EXPECT_EQ(paint.base().roughness, 0.2f);
    EXPECT_EQ(paint.base().ior, glm::vec3(1.45f));
    EXPECT_EQ(frosted.layers[0].roughness, 0.2f);
    EXPECT_EQ(frosted.base().roughness, 0.001f);
    EXPECT_EQ(frosted.base().ior, glm::vec3(1.45f));
    EXPECT_EQ(slab.layers[0].roughness, 0.001f);
    EXPECT_EQ(slab.base().roughness, 0.2f);
    EXPECT_EQ(slab.base().ior, glm::vec3(1.0f));
    EXPECT_TRUE(slab.transmissive());
    EXPECT_FALSE(plastic.transmissive() || paint.transmissive() || frosted.transmissive());
}

TEST(BadStacks, EachIsRefusedAsExpected) {
    const auto files = toml_files(kRoot / "tests" / "bad_stacks");
    ASSERT_GE(files.size(), 20u) << "tests/bad_stacks should hold at least 20 malformed stacks";
    const std::regex expect_re(R"(^# expect: line (\d+): (.+?)\s*$)");
    for (const auto& f : files) {
        SCOPED_TRACE(f.string());
        std::ifstream in(f);
        std::string first;
        std::getline(in, first);
        std::smatch m;
        ASSERT_TRUE(std::regex_match(first, m, expect_re)) << "first line must be '# expect: line N: <substring>'";
        const int line = std::stoi(m[1]);
        const std::string sub = m[2];
        try {
            parse_stack_file(f.string());
            ADD_FAILURE() << "accepted, expected an error at line " << line << ": " << sub;
        } catch (const StackError& e) {
            const std::string what = e.what(), prefix = f.string() + ":" + std::to_string(line) + ":";
            EXPECT_EQ(what.rfind(prefix, 0), 0u) << "message: " << what << "\nexpected prefix: " << prefix;
            EXPECT_NE(what.find(sub), std::string::npos) << "message: " << what << "\nexpected to contain: " << sub;
            EXPECT_EQ(e.file, f.string());
            EXPECT_EQ(e.line, line);
        }
    }
}

// A scattering medium: its keys, their defaults, which media scatter, the description and the round trip.
TEST(Stack, ScatteringMediumKeys) {
    const Stack s = parse_stack_string(R"(name = "t"
[[layer]]
interface = "dielectric"
ior = 1.5
optical_depth = [1, 0, 2]
scattering_albedo = [0.8, 0.9, 0]
phase_g = -0.25

[[layer]]
interface = "dielectric"
ior = 1.3
optical_depth = 0.5

[[layer]]
interface = "lambertian"
albedo = 0.5
)",
                                       "t.toml");
    EXPECT_EQ(s.layers[0].scattering_albedo, glm::vec3(0.8f, 0.9f, 0.0f));
    EXPECT_EQ(s.layers[0].phase_g, -0.25f);
    EXPECT_EQ(s.layers[1].scattering_albedo, glm::vec3(0.0f));   // default: the medium only absorbs
    EXPECT_EQ(s.layers[1].phase_g, 0.0f);
    // red scatters (tau 1, albedo 0.8); green has albedo but no optical depth, blue depth but no albedo
    EXPECT_TRUE(s.medium_scatters(0));
    EXPECT_FALSE(s.medium_scatters(1));
    EXPECT_FALSE(s.medium_scatters(2));
    const std::string d = describe_stack(s);
    EXPECT_NE(d.find("Henyey-Greenstein g -0.25"), std::string::npos) << d;
    const Stack back = parse_stack_string(stack_to_toml(s), "back.toml");
    EXPECT_EQ(back.layers[0].scattering_albedo, s.layers[0].scattering_albedo);
    EXPECT_EQ(back.layers[0].phase_g, s.layers[0].phase_g);
    EXPECT_EQ(back.layers[0].optical_depth, s.layers[0].optical_depth);
    EXPECT_EQ(stack_to_toml(back), stack_to_toml(s));
    // albedo with no optical depth anywhere: nothing scatters, and `check` says the keys have no effect
    const Stack clear = parse_stack_string(R"(name = "t"
[[layer]]
interface = "dielectric"
ior = 1.5
scattering_albedo = 0.5
[[layer]]
interface = "lambertian"
albedo = 0.5
)",
                                           "clear.toml");
    EXPECT_FALSE(clear.medium_scatters(0));
    EXPECT_NE(describe_stack(clear).find("no effect"), std::string::npos);
}

TEST(Stack, ScalarsBroadcastAndDefaults) {
    const Stack s = parse_stack_string(R"(name = "t"
[[layer]]
interface = "dielectric"
ior = 2

[[layer]]
interface = "conductor"
roughness = 0.3
ior = 1.45
k = [3, 2, 1]
)",
                                       "t.toml");
    EXPECT_EQ(s.exterior_ior, 1.0f);
    EXPECT_EQ(s.description, "");
    EXPECT_EQ(s.source_path, "t.toml");
    ASSERT_EQ(s.layers.size(), 2u);
    EXPECT_EQ(s.layers[0].roughness, 0.0f);
    EXPECT_EQ(s.layers[0].ior, glm::vec3(2.0f));   // integer accepted, broadcast
    EXPECT_EQ(s.layers[0].optical_depth, glm::vec3(0.0f));
    EXPECT_EQ(s.layers[0].line, 2);
    EXPECT_EQ(s.layers[1].line, 6);
    EXPECT_EQ(s.layers[1].ior, glm::vec3(1.45f));
    EXPECT_EQ(s.layers[1].k, glm::vec3(3, 2, 1));
    EXPECT_EQ(parse_stack_string(kTwoLayers, "t").base().albedo, glm::vec3(0.25f));
}

TEST(Stack, TransmissiveAndIorAbove) {
    Stack s = parse_stack_string(R"(name = "slab"
exterior_ior = 1.33
[[layer]]
interface = "dielectric"
ior = [1.5, 1.5, 1.5]
optical_depth = 0.2
[[layer]]
interface = "dielectric"
ior = 1.2
)",
                                 "t");
    EXPECT_TRUE(s.transmissive());
    EXPECT_EQ(s.ior_above(0), glm::vec3(1.33f));
    EXPECT_EQ(s.ior_above(1), glm::vec3(1.5f));
    EXPECT_FALSE(parse_stack_string(kTwoLayers, "t").transmissive());
    const std::string d = describe_stack(s);
    EXPECT_NE(d.find("transmissive"), std::string::npos) << d;
    EXPECT_NE(d.find("critical angle"), std::string::npos) << d;
}

TEST(Stack, ValidateBuiltInCode) {
    Stack s;
    s.name = "code";
    Layer coat;
    coat.ior = glm::vec3(1.5f);
    Layer metal;
    metal.kind = InterfaceKind::Conductor;
    metal.ior = glm::vec3(0.2f);
    metal.k = glm::vec3(3.0f);
    s.layers = {coat, metal};
    EXPECT_NO_THROW(validate_stack(s));
    Stack back = parse_stack_string(stack_to_toml(s), "rt");
    expect_same_values(s, back);

    s.layers = {metal, coat};
    std::string w = error_of([&] { validate_stack(s); });
    EXPECT_EQ(w.rfind(":0: layer 1: misplaced base", 0), 0u) << w;

    s.layers = {coat, metal};
    s.layers[1].roughness = -0.5f;
    w = error_of([&] { validate_stack(s); });
    EXPECT_NE(w.find("roughness must be in [1e-04, 1] or 0"), std::string::npos) << w;

    s.layers = std::vector<Layer>(kMaxLayers + 1, coat);
    w = error_of([&] { validate_stack(s); });
    EXPECT_NE(w.find("at most 16 layers"), std::string::npos) << w;

    s.layers = {coat};
    s.layers[0].optical_depth = glm::vec3(0.1f);   // a lone dielectric is the substrate interface
    w = error_of([&] { validate_stack(s); });
    EXPECT_NE(w.find("semi-infinite"), std::string::npos) << w;
}

TEST(Stack, MissingFileIsAStackError) {
    const std::string w = error_of([] { parse_stack_file("/nonexistent/stack.toml"); });
    EXPECT_EQ(w.rfind("/nonexistent/stack.toml:", 0), 0u) << w;
}

TEST(Stack, StringsRoundTripWithEscapes) {
    Stack s = parse_stack_string(kTwoLayers, "t");
    s.name = "quote \" back\\slash";
    s.description = "line\nbreak\ttab \x01 ctrl, unicode \xc3\xa9";
    const Stack back = parse_stack_string(stack_to_toml(s), "rt");
    expect_same_values(s, back);
}

// stacks/README.md's key table is the vocabulary's (host/core/stack_vocabulary.h), row for row: a key added, removed
// or given another range without the README following fails here (the expected table is printed).
TEST(Vocabulary, ReadmeKeyTableIsTheVocabularys) {
    std::ifstream in(kRoot / "stacks" / "README.md");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string begin = "<!-- keys: the table of host/core/stack_vocabulary.cpp -->\n", end = "<!-- /keys -->";
    const size_t a = text.find(begin), b = text.find(end);
    ASSERT_NE(a, std::string::npos) << "stacks/README.md lacks the marker " << begin;
    ASSERT_NE(b, std::string::npos);
    EXPECT_EQ(text.substr(a + begin.size(), b - a - begin.size()), keys_markdown_table())
        << "stacks/README.md's key table should read:\n"
        << keys_markdown_table();
}

// The other lists of the keys follow the vocabulary: docs/SWEEPS.md's `[[vary]]` key line names every key, and a user
// model's GonioLayer (shaders/lib/models/user_model.glsl) has a member of every key's name
TEST(Vocabulary, SweepDocsAndUserModelLayerNameEveryKey) {
    auto read = [](const std::filesystem::path& p) {
        std::ifstream in(p);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    const std::string sweeps = read(kRoot / "docs" / "SWEEPS.md"),
                      glsl = read(kRoot / "shaders" / "lib" / "models" / "user_model.glsl");
    std::string names;
    for (const std::string& k : layer_key_names()) names += (names.empty() ? "" : ", ") + k;
    EXPECT_NE(sweeps.find("# keys: " + names + "\n"), std::string::npos)
        << "docs/SWEEPS.md's [[vary]] key line should read: # keys: " << names;
    const size_t a = glsl.find("struct GonioLayer {"), b = glsl.find("};", a);
    ASSERT_NE(a, std::string::npos);
    const std::string layer = glsl.substr(a, b - a);
    for (const std::string& k : layer_key_names())
        EXPECT_TRUE(std::regex_search(layer, std::regex("\\b(float|vec3|uint) " + k + ";")))
            << "user_model.glsl's GonioLayer lacks " << k;
}

// Every kind has keys and every key one place in Layer; the writer and the parser agree on every key of every kind:
// a layer with each key set away from its default reads back to the same values (each word key at its other word).
TEST(Vocabulary, EveryKeyRoundTrips) {
    for (const KindInfo& kind : interface_kinds()) {
        SCOPED_TRACE(kind.name);
        ASSERT_FALSE(keys_of(kind.kind).empty());
        Stack s;
        s.name = "v";
        Layer coat;
        coat.ior = glm::vec3(1.5f);
        Layer y;
        y.kind = kind.kind;
        for (const LayerKey* key : keys_of(kind.kind)) {   // a value inside the range, away from the default
            const float lo = key->range.lo, hi = std::min(key->range.hi, 2.0f);
            key->set(y, glm::vec3(lo + 0.375f * (hi - lo)));
        }
        // a microflake medium's alpha goes with its phase word, not with Henyey-Greenstein's g: below, with the word
        const float fibre_roughness = y.fibre_roughness;
        y.fibre_roughness = 0.0f;
        const size_t at = kind.opaque ? 1 : 0;   // a base under a coat, a dielectric over a substrate
        s.layers = kind.opaque ? std::vector<Layer>{coat, y} : std::vector<Layer>{y, coat};
        for (const ChoiceKey& c : choice_keys())   // a word at its default is not written (today's files)
            EXPECT_EQ(stack_to_toml(s).find(std::string(c.name) + " ="), std::string::npos) << c.name;
        const Stack back = parse_stack_string(stack_to_toml(s), "v.toml");
        for (const LayerKey* key : keys_of(kind.kind))
            EXPECT_EQ(key->get(back.layers[at]), key->get(s.layers[at])) << key->name;
        // each word key's other word, one at a time (separable shadowing and multiple microfacets are refused
        // together: bad_stacks/microfacets-multiple-separable.toml)
        for (const ChoiceKey& c : choice_keys()) {
            if (!c.of_kind(kind.kind)) continue;
            for (int word = 1; word < c.word_count(); ++word) {
                Stack w = s;
                c.set(w.layers[at], word);
                if (c.medium) {   // a microflake medium: its alpha, and no g
                    w.layers[at].fibre_roughness = fibre_roughness;
                    w.layers[at].phase_g = 0.0f;
                }
                const Stack b = parse_stack_string(stack_to_toml(w), "v.toml");
                EXPECT_EQ(c.get(b.layers[at]), word) << c.name;
                EXPECT_EQ(b.layers[at].fibre_roughness, w.layers[at].fibre_roughness) << c.name;
            }
        }
    }
}
