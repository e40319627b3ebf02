// A model file's header (host/models/model_file.h): what it says is read back, every malformed header is refused
// with FILE:LINE, and the stack shapes it may name match the stacks they describe.
#include "model_file.h"
#include "stack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace {

using namespace gonio;

const std::string kGood = R"(
// gonio-model: my-coat
// citation: Doe 2027, "A better coat",
//   eq. 3
// represents: coat-over-lambertian, coat-over-conductor
// reciprocal: yes
// energy-conserving: no (the base is not attenuated by the coat's reflection)
#include "ggx.glsl"
vec3 model_f(vec3 l, vec3 v) { return vec3(1.0f / 3.14159265f); }
)";

TEST(ModelFile, HeaderIsReadBack) {
    ModelFileHeader h = parse_model_header(kGood, "my_coat.glsl");
    EXPECT_EQ(h.id, "my-coat");
    EXPECT_EQ(h.citation, "Doe 2027, \"A better coat\", eq. 3");
    ASSERT_EQ(h.represents.size(), 2u);
    EXPECT_EQ(h.represents[0], StackShape::CoatOverLambertian);
    EXPECT_EQ(h.represents[1], StackShape::CoatOverConductor);
    EXPECT_TRUE(h.reciprocal);
    EXPECT_FALSE(h.energy_conserving);
    EXPECT_EQ(h.energy_note, "the base is not attenuated by the coat's reflection");
    EXPECT_FALSE(h.has_lobe_hints);
    std::string with_lobes = kGood + "uint model_lobes(vec3 l, out GonioLobe lobes[GONIO_MAX_LOBES]) { return 0u; }\n";
    EXPECT_TRUE(parse_model_header(with_lobes, "m.glsl").has_lobe_hints);
    // a mention in a comment is not a definition
    EXPECT_FALSE(parse_model_header(kGood + "// no uint model_lobes(...) here\n", "m.glsl").has_lobe_hints);
}

// A model file is data from outside: a long header line or key value is refused with its line before any pattern
// runs on it, and the entry is found by a linear scan (std::regex recursed once per character and overflowed the stack
// on a header line of 94 000 characters: SIGSEGV), wherever its tokens are split (spaces, tabs, newlines)
TEST(ModelFile, LongInputsAreRefusedOrScannedNotRecursed) {
    auto refused_at = [](const std::string& text, const std::string& says) {
        try {
            parse_model_header(text, "m.glsl");
            ADD_FAILURE() << "accepted";
        } catch (const StackError& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
            return e.line;
        }
        return 0;
    };
    std::string long_line = kGood;
    long_line.insert(long_line.find("// represents"), "// c" + std::string(94000, 'x') + "\n");
    EXPECT_EQ(refused_at(long_line, "a header line of 94004 characters (at most 1000)"), 5);
    std::string long_value = kGood;
    std::string more;
    for (int i = 0; i < 20; ++i) more += "//   " + std::string(500, 'y') + "\n";
    long_value.insert(long_value.find("// represents"), more);
    EXPECT_EQ(refused_at(long_value, "citation: its value runs over 8000 characters"), 20);
    // the entry split over lines and spaced out; a long run of spaces after `vec3` that is not the entry
    const std::string split = "// gonio-model: m\nvec3" + std::string(200000, ' ') +
                              "x;\nvec3\n  model_f (\tvec3 l ,\n"
                              "vec3   v\n)\n{ return l; }\n";
    EXPECT_EQ(parse_model_header(split, "m.glsl").id, "m");
    EXPECT_EQ(refused_at("// gonio-model: m\nvec3 model_f(vec3 l, vec3" + std::string(200000, ' ') + ")\n",
                         "defines no 'vec3 model_f(vec3 l, vec3 v)'"),
              1);
    EXPECT_EQ(refused_at("// gonio-model: m\nvec3 model_fx(vec3 l, vec3 v) {}\nfloat model_f(vec3 l, vec3 v) {}\n",
                         "defines no 'vec3 model_f"),
              1);
    EXPECT_TRUE(parse_model_header(kGood + "  \tuint  model_lobes (vec3 l) { return 0u; }\n", "m.glsl").has_lobe_hints);
}

// A user's file needs only its id: without `represents:` it runs on every stack; without `reciprocal:` and
// `energy-conserving:` it claims neither (gonio measures both), and says so (states_*), unlike a file that says no.
TEST(ModelFile, AUserFileNeedsOnlyItsId) {
    const ModelFileHeader h =
        parse_model_header("// gonio-model: bare\nvec3 model_f(vec3 l, vec3 v) { return vec3(0.1f); }\n", "bare.glsl");
    EXPECT_EQ(h.id, "bare");
    ASSERT_EQ(h.represents.size(), 1u);
    EXPECT_EQ(h.represents[0], StackShape::Any);
    EXPECT_FALSE(h.states_reciprocity);
    EXPECT_FALSE(h.states_energy);
    const ModelFileHeader g = parse_model_header(kGood, "my_coat.glsl");
    EXPECT_TRUE(g.states_reciprocity);
    EXPECT_TRUE(g.states_energy);
    const ModelFileHeader no = parse_model_header(
        "// gonio-model: no\n// reciprocal: no\nvec3 model_f(vec3 l, vec3 v) { return l; }\n", "no.glsl");
    EXPECT_TRUE(no.states_reciprocity);
    EXPECT_FALSE(no.reciprocal);
    EXPECT_FALSE(no.states_energy);
}

// A model's own parameters: name, default, range and meaning read back in order; each malformed or inconsistent one
// refused with its line
TEST(ModelFile, ParametersAreReadAndChecked) {
    const std::string body = "vec3 model_f(vec3 l, vec3 v) { return vec3(param_a * param_b2); }\n";
    const ModelFileHeader h = parse_model_header(
        "// gonio-model: p\n"
        "// parameter: a default 0.25 range [0, 1] -- the scale\n"
        "// parameter: b2 default -1e-2 range [-0.5, 2.5e1]\n" +
            body,
        "p.glsl");
    ASSERT_EQ(h.parameters.size(), 2u);
    EXPECT_EQ(h.parameters[0].name, "a");
    EXPECT_EQ(h.parameters[0].value, 0.25);
    EXPECT_EQ(h.parameters[0].lo, 0.0);
    EXPECT_EQ(h.parameters[0].hi, 1.0);
    EXPECT_EQ(h.parameters[0].meaning, "the scale");
    EXPECT_EQ(h.parameters[0].line, 2);
    EXPECT_EQ(h.parameters[1].name, "b2");
    EXPECT_EQ(h.parameters[1].value, -0.01);
    EXPECT_EQ(h.parameters[1].lo, -0.5);
    EXPECT_EQ(h.parameters[1].hi, 25.0);
    EXPECT_EQ(h.parameters[1].meaning, "");
    auto refused = [&](const std::string& lines, const std::string& says) {
        try {
            parse_model_header("// gonio-model: p\n" + lines + body, "p.glsl");
            ADD_FAILURE() << "accepted: " << lines;
        } catch (const StackError& e) { EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what(); }
    };
    refused("// parameter: a 0.25 [0, 1]\n", "p.glsl:2: parameter: expected 'NAME default VALUE range [A, B]");
    refused("// parameter: A default 0.25 range [0, 1]\n", "p.glsl:2: parameter: expected");
    refused("// parameter: a default 2 range [0, 1]\n", "p.glsl:2: parameter a: expected A < B and the default within");
    refused("// parameter: a default 0.5 range [1, 0]\n", "p.glsl:2: parameter a: expected A < B");
    refused("// parameter: a default 0.5 range [0, 1]\n// parameter: a default 0.5 range [0, 1]\n",
            "p.glsl:3: parameter a: given twice (first at line 2)");
    std::string nine;
    for (int i = 0; i < 9; ++i) nine += "// parameter: p" + std::to_string(i) + " default 0 range [0, 1]\n";
    refused(nine, "p.glsl:10: parameter p8: a model has at most 8 parameters");
}

// the text with line `line` (1-based) replaced
std::string with_line(const std::string& text, int line, const std::string& replacement) {
    std::string out;
    int n = 0;
    size_t pos = 0;
    while (pos <= text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        ++n;
        out += (n == line ? replacement : text.substr(pos, end - pos));
        if (end < text.size()) out += "\n";
        pos = end + 1;
    }
    return out;
}

void expect_refused(const std::string& text, const std::string& where, const std::string& says) {
    try {
        parse_model_header(text, "m.glsl");
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const StackError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind(where, 0), 0u) << m;
        EXPECT_NE(m.find(says), std::string::npos) << m;
    }
}

TEST(ModelFile, MalformedHeadersAreRefusedWithTheirLine) {
    expect_refused(with_line(kGood, 2, "// model: my-coat"), "m.glsl:2:", "start with '// gonio-model: ID'");
    expect_refused(with_line(kGood, 2, "// gonio-model: My Coat"), "m.glsl:2:", "lower-case letters");
    expect_refused(with_line(kGood, 5, "// represents: coat-over-lambertian, coat-over-glass"),
                   "m.glsl:5:", "unknown stack shape 'coat-over-glass'");
    expect_refused(with_line(kGood, 6, "// reciprocal: maybe"), "m.glsl:6:", "expected yes or no");
    expect_refused(with_line(kGood, 7, "// energy-conserving: no, mostly"), "m.glsl:7:", "expected yes or no");
    expect_refused(with_line(kGood, 6, "// reciprocity: yes"), "m.glsl:6:", "unknown header key 'reciprocity:'");
    expect_refused(with_line(kGood, 6, "// gonio-model: again"), "m.glsl:6:", "given twice (first on line 2)");
    expect_refused(with_line(kGood, 9, "float model_f(vec3 l, vec3 v) { return 0.0f; }"),
                   "m.glsl:2:", "defines no 'vec3 model_f(vec3 l, vec3 v)'");
    expect_refused("vec3 model_f(vec3 l, vec3 v) { return vec3(0.0f); }\n", "m.glsl:1:", "gonio-model");
    expect_refused("", "m.glsl:1:", "gonio-model");
}

// A line indented after its "//" continues the one above, even where it reads "word: ...": prose in a citation or
// a built-in's note is not taken for a key (unindented, it is one, and an unknown key is refused as above)
TEST(ModelFile, AnIndentedLineIsNeverAKey) {
    const ModelFileHeader h = parse_model_header(with_line(kGood, 4, "//   eq. 3, note: the second form"), "m.glsl");
    EXPECT_EQ(h.citation, "Doe 2027, \"A better coat\", eq. 3, note: the second form");
    const ModelFileHeader p = parse_model_header(with_line(kGood, 4, "//   note: the second form"), "m.glsl");
    EXPECT_EQ(p.citation, "Doe 2027, \"A better coat\", note: the second form");
    expect_refused(with_line(kGood, 4, "// note: the second form"), "m.glsl:4:", "unknown header key 'note:'");
    // the first line is the id's, indented or not
    EXPECT_EQ(parse_model_header("//   gonio-model: x\nvec3 model_f(vec3 l, vec3 v) { return l; }\n", "x.glsl").id,
              "x");
}

Layer dielectric(float ior) {
    Layer L;
    L.kind = InterfaceKind::Dielectric;
    L.ior = glm::vec3(ior);
    return L;
}
Layer conductor() {
    Layer L;
    L.kind = InterfaceKind::Conductor;
    L.ior = glm::vec3(0.2f);
    L.k = glm::vec3(3.0f);
    return L;
}
Layer lambertian() {
    Layer L;
    L.kind = InterfaceKind::Lambertian;
    L.albedo = glm::vec3(0.5f);
    return L;
}
Stack stack_of(std::vector<Layer> layers) {
    Stack s;
    s.name = "t";
    s.layers = std::move(layers);
    return s;
}

TEST(ModelFile, StackShapesMatchTheirStacks) {
    const Stack plastic = stack_of({dielectric(1.5f), lambertian()});
    const Stack coated_metal = stack_of({dielectric(1.5f), conductor()});
    const Stack two_coats_metal = stack_of({dielectric(1.5f), dielectric(1.3f), conductor()});
    const Stack bare_metal = stack_of({conductor()});
    const Stack slab = stack_of({dielectric(1.5f), dielectric(1.0f)});
    const Stack glass_on_water = stack_of({dielectric(1.5f), dielectric(1.33f)});
    const Stack lambertian_over_metal = stack_of({lambertian(), conductor()});
    struct Want {
        StackShape shape;
        std::vector<const Stack*> yes;
    };
    const std::vector<const Stack*> all = {&plastic, &coated_metal,   &two_coats_metal,      &bare_metal,
                                           &slab,    &glass_on_water, &lambertian_over_metal};
    const std::vector<Want> wants = {
        {StackShape::Any, all},
        {StackShape::CoatOverLambertian, {&plastic}},
        {StackShape::CoatOverConductor, {&coated_metal}},
        {StackShape::DielectricsOverLambertian, {&plastic}},
        {StackShape::DielectricsOverConductor, {&coated_metal, &two_coats_metal, &bare_metal}},
        {StackShape::Slab, {&slab}},
        {StackShape::Transmissive, {&slab, &glass_on_water}},
    };
    for (const Want& w : wants)
        for (const Stack* s : all) {
            const bool want = std::find(w.yes.begin(), w.yes.end(), s) != w.yes.end();
            EXPECT_EQ(stack_has_shape(*s, w.shape), want)
                << to_string(w.shape) << " on the stack #" << (std::find(all.begin(), all.end(), s) - all.begin());
        }
    ModelFileHeader h = parse_model_header(kGood, "my_coat.glsl");
    EXPECT_EQ(model_file_cannot_represent(h, plastic), "");
    EXPECT_EQ(model_file_cannot_represent(h, slab),
              "my-coat represents coat-over-lambertian, coat-over-conductor (its header, my_coat.glsl); this stack is "
              "none of them");
}

}   // namespace

namespace {
const std::string kBuiltIn = R"(// gonio-model: my-builtin
// citation: Doe 2027
// summary: a coat
// stacks: one coat over a Lambertian base
// represents: coat-over-lambertian
// reciprocal: yes
// energy-conserving: yes
// plan: coat
// refuses: transmissive = {id} models reflection only; this stack
//   is transmissive
// refuses: not-two-layers = {id} takes two layers, not {layers}
// family: tests
//
vec3 model_my_builtin(CoatParams p, uint terms, vec3 l, vec3 v) { return vec3(0.0f); }
)";
}   // namespace

// A built-in's plan and refusals: read back, their reasons filled in order, the shapes after them; an unknown plan or
// condition refused with its line.
TEST(ModelFile, PlanAndRefusalsOfABuiltIn) {
    const ModelFileHeader h = parse_model_header(kBuiltIn, "b.glsl", ModelFileKind::BuiltIn);
    EXPECT_EQ(h.plan, PlanKind::Coat);
    ASSERT_EQ(h.refuses.size(), 2u);
    EXPECT_EQ(h.refuses[0].when, StackCondition::Transmissive);
    EXPECT_EQ(h.refuses[1].line, 11);
    auto stack = [](const char* text) { return parse_stack_string(text, "s.toml"); };
    const Stack slab = stack("name = \"s\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n");
    EXPECT_EQ(model_file_cannot_represent(h, slab, "my-builtin+x"),
              "my-builtin+x models reflection only; this stack is transmissive");
    const Stack three = stack(
        "name = \"s\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n[[layer]]\ninterface = \"dielectric\"\n"
        "ior = 1.3\n[[layer]]\ninterface = \"lambertian\"\nalbedo = 0.5\n");
    EXPECT_EQ(model_file_cannot_represent(h, three), "my-builtin takes two layers, not 3");
    const Stack metal = stack(
        "name = \"s\"\n[[layer]]\ninterface = \"dielectric\"\nior = 1.5\n[[layer]]\ninterface = \"conductor\"\n"
        "ior = 1\nk = 3\n");
    EXPECT_NE(model_file_cannot_represent(h, metal).find("represents coat-over-lambertian"), std::string::npos);
    auto refused_at = [](std::string text, const std::string& from, const std::string& to) {
        text.replace(text.find(from), from.size(), to);
        try {
            parse_model_header(text, "b.glsl", ModelFileKind::BuiltIn);
        } catch (const StackError& e) { return e.line; }
        return 0;
    };
    EXPECT_EQ(refused_at(kBuiltIn, "plan: coat", "plan: spline"), 8);
    EXPECT_EQ(refused_at(kBuiltIn, "refuses: transmissive", "refuses: opaque"), 9);
    // a user's file takes neither key
    std::string user = kGood;
    user.replace(user.find("#include"), 0, "// plan: coat\n");
    EXPECT_THROW(parse_model_header(user, "u.glsl"), StackError);
}
