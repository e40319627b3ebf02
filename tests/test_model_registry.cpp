// The registry of built-in models is made from their files (host/models/model_registry.h; docs/MODELS.md "How to add
// a model"): it lists exactly the files of shaders/lib/models/builtin/ (embedded in the binary as they are in the
// source tree), in name order, each with the fields of its header, then their variants; a new file is a new model
// (code = its place) that model_plan.cpp has no plan for, integrated as a black box and representing the shapes of
// its header; the built-in header's own keys are read and refused as a user's are.
#include "model_applicability.h"
#include "model_plan.h"
#include "model_registry.h"
#include "model_twin.h"   // the build's table-set layout (STACK_TABLE_SET_LIST)
#include "random_stack.h"
#include "stack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

using namespace gonio;

const std::string kSource = GONIO_SOURCE_DIR;

std::string read(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// shaders/lib/models/builtin/*.glsl as the source tree has them, in name order
std::vector<BuiltinModelFile> source_files() {
    std::vector<BuiltinModelFile> files;
    for (const auto& e : std::filesystem::directory_iterator(kSource + "/shaders/lib/models/builtin"))
        if (e.path().extension() == ".glsl")
            files.push_back({"shaders/lib/models/builtin/" + e.path().filename().string(), read(e.path())});
    std::sort(files.begin(), files.end(),
              [](const BuiltinModelFile& a, const BuiltinModelFile& b) { return a.path < b.path; });
    return files;
}

TEST(ModelRegistry, ListsExactlyTheFilesOfTheBuiltinFolder) {
    const std::vector<BuiltinModelFile> src = source_files(), embedded = builtin_model_files();
    ASSERT_EQ(embedded.size(), src.size());
    for (size_t i = 0; i < src.size(); ++i) {
        EXPECT_EQ(embedded[i].path, src[i].path);
        EXPECT_EQ(embedded[i].text, src[i].text) << src[i].path << ": the binary embeds another text";
    }
    const auto& r = model_registry();
    size_t variants = 0;
    for (size_t i = 0; i < src.size(); ++i) {
        const ModelFileHeader h = parse_model_header(src[i].text, src[i].path, ModelFileKind::BuiltIn);
        const ModelInfo& m = r.at(i);
        EXPECT_EQ(m.id, h.id);
        EXPECT_EQ(m.citation, h.citation);
        EXPECT_EQ(m.summary, h.summary);
        EXPECT_EQ(m.represents, h.stacks);
        EXPECT_EQ(m.reciprocal, h.reciprocal);
        EXPECT_EQ(m.energy_conserving, h.energy_conserving);
        EXPECT_EQ(m.energy_note, h.energy_note);
        EXPECT_EQ(m.shader_model, uint32_t(i));
        EXPECT_EQ(m.convention, 0u);
        EXPECT_EQ(m.file, src[i].path);
        EXPECT_EQ(code_id(uint32_t(i)), h.id);
        variants += h.variants.size();
    }
    ASSERT_EQ(r.size(), src.size() + variants);
    // the variants, after the base models, in the files' order and each file's
    size_t k = src.size();
    for (size_t i = 0; i < src.size(); ++i)
        for (const ModelVariant& v : r[i].header.variants) {
            const ModelInfo& m = r.at(k++);
            EXPECT_EQ(m.id, r[i].id + v.suffix);
            const bool gonios = (v.convention & (MODEL_CONVENTION_G2 | MODEL_CONVENTION_TIR_BELOW_MEDIA)) != 0;
            EXPECT_EQ(m.citation,
                      (gonios ? "gonio's variant of " : "a variant of ") + r[i].id + " (" + r[i].citation + ")");
            EXPECT_EQ(m.summary, "as " + r[i].id + ", " + v.what);
            EXPECT_EQ(m.represents, r[i].represents);
            EXPECT_EQ(m.reciprocal, v.has_reciprocal ? v.reciprocal : r[i].reciprocal);
            EXPECT_EQ(m.energy_conserving, r[i].energy_conserving);
            EXPECT_EQ(m.energy_note, v.has_energy_note ? v.energy_note : r[i].energy_note);
            EXPECT_EQ(m.shader_model, uint32_t(i));
            EXPECT_EQ(m.convention, v.convention);
            EXPECT_NE(m.convention, 0u);
        }
}

// what gonio ships: the sixteen models in their order, each with its plan (its file's `plan:`), and their variants
TEST(ModelRegistry, TheShippedModelsKeepTheirCodesAndPlans) {
    const std::vector<std::pair<std::string, PlanKind>> shipped = {
        {"ww09", PlanKind::Coat},
        {"elek10", PlanKind::CoatRefracted},
        {"ww-corrected", PlanKind::CoatRefracted},
        {"albedo-scaling", PlanKind::Coat},
        {"belcour18-forward", PlanKind::Lobes},
        {"belcour18-symmetric", PlanKind::LobesSymmetric},
        {"belcour18-toplobe", PlanKind::Lobes},
        {"tm21", PlanKind::Lobes},
        {"gltf-clearcoat", PlanKind::Coat},
        {"openpbr", PlanKind::Coat},
        {"enterprise-pbr", PlanKind::Coat},
        {"standard-surface", PlanKind::Coat},
        {"materialx-layer", PlanKind::Coat},
        {"cycles-principled", PlanKind::Coat},
        {"openpbr-adobe", PlanKind::Coat},
        {"interfaced-lambertian", PlanKind::Coat},
        {"zeltner22-sheen", PlanKind::BlackBox},
        {"charlie-sheen", PlanKind::BlackBox},
        {"gltf-sheen", PlanKind::BlackBox},
        {"materialx-sheen", PlanKind::BlackBox},
        {"standard-surface-sheen", PlanKind::BlackBox},
        {"cycles-sheen", PlanKind::BlackBox},
    };
    for (size_t i = 0; i < shipped.size(); ++i) {
        EXPECT_EQ(code_id(uint32_t(i)), shipped[i].first);
        EXPECT_EQ(plan_kind(uint32_t(i)), shipped[i].second) << shipped[i].first;
        EXPECT_EQ(plan_kind_of(shipped[i].first), shipped[i].second);
    }
    // the production models and the sheen models say what their parameters are for a stack (`mapping:`, printed by
    // `gonio models`: a fibre layer has no coat's parameters); the research models take the stack's own parameters
    for (const ModelInfo& m : model_registry()) {
        const bool production = m.header.id == "gltf-clearcoat" || m.header.id == "openpbr" ||
                                m.header.id == "enterprise-pbr" || m.header.id == "standard-surface" ||
                                m.header.id == "materialx-layer" || m.header.id == "cycles-principled" ||
                                m.header.id == "openpbr-adobe" || m.header.id == "interfaced-lambertian" ||
                                m.header.family == "sheen";   // and the variants
        EXPECT_EQ(m.header.mapping.empty(), !production) << m.id;
    }
    std::vector<std::string> ids;
    for (const ModelInfo& m : model_registry()) ids.push_back(m.id);
    const std::vector<std::string> variants = {"belcour18-forward+g2",     "belcour18-forward+tir",
                                               "belcour18-forward+g2+tir", "belcour18-symmetric+g2",
                                               "belcour18-symmetric+tir",  "belcour18-symmetric+g2+tir",
                                               "belcour18-toplobe+g2",     "belcour18-toplobe+tir",
                                               "belcour18-toplobe+g2+tir", "tm21+g2",
                                               "gltf-clearcoat+viewer",    "openpbr+dev1.2",
                                               "openpbr+materialx",        "openpbr+pr261",
                                               "openpbr+separable",        "openpbr+numerator",
                                               "openpbr+single",           "standard-surface+osl",
                                               "cycles-principled+4.4",    "openpbr-adobe+reciprocal"};
    ASSERT_EQ(ids.size(), shipped.size() + variants.size());
    for (size_t i = 0; i < variants.size(); ++i) EXPECT_EQ(ids[shipped.size() + i], variants[i]);
}

// A new file in the folder is a new model: code = its place, its variants after the others', no plan (a black
// box), the shapes of its header for what it represents
TEST(ModelRegistry, ANewFileIsANewModel) {
    std::vector<BuiltinModelFile> files = source_files();
    const std::string extra = kSource + "/tests/builtin_models/99-test-coat-rewrite.glsl";
    files.push_back({"shaders/lib/models/builtin/99-test-coat-rewrite.glsl", read(extra)});
    const std::vector<ModelInfo> r = make_model_registry(files);
    const size_t code = files.size() - 1;
    ASSERT_EQ(r.size(), model_registry().size() + 2);
    // the shipped entries are unchanged, the new base model comes after the shipped base models
    for (size_t i = 0; i < code; ++i) EXPECT_EQ(r[i].id, model_registry()[i].id);
    const ModelInfo& m = r[code];
    EXPECT_EQ(m.id, "test-coat-rewrite");
    EXPECT_EQ(m.shader_model, uint32_t(code));
    EXPECT_EQ(
        m.citation,
        "gonio's tests: ww-corrected (Bati, Pacanowski & Barla 2019, eq. 4) as a new built-in model with no plan");
    EXPECT_EQ(m.summary, "the f of ww-corrected, both terms, integrated as a black box");
    EXPECT_EQ(m.header.family, "tests");
    EXPECT_EQ(m.represents, "one dielectric coat over a Lambertian or conductor base");
    EXPECT_TRUE(m.reciprocal);
    EXPECT_TRUE(m.energy_conserving);
    EXPECT_EQ(m.header.plan, PlanKind::BlackBox);
    const ModelInfo& v = r.back();
    EXPECT_EQ(v.id, "test-coat-rewrite+g2");
    EXPECT_EQ(v.shader_model, uint32_t(code));
    EXPECT_EQ(v.convention, MODEL_CONVENTION_G2);
    EXPECT_EQ(v.summary, "as test-coat-rewrite, with the g2 bit set (which this model does not read)");
    EXPECT_EQ(v.energy_note, "as test-coat-rewrite");
    // what it represents: its header's shapes (model_file_cannot_represent)
    const Stack coat = parse_stack_file(kSource + "/stacks/plastic.toml");
    EXPECT_EQ(model_file_cannot_represent(m.header, coat), "");
    const Stack slab = parse_stack_file(kSource + "/stacks/transparent-slab.toml");
    const std::string why = model_file_cannot_represent(m.header, slab);
    EXPECT_NE(why.find("test-coat-rewrite represents coat-over-lambertian, coat-over-conductor"), std::string::npos)
        << why;
    EXPECT_NE(why.find("shaders/lib/models/builtin/99-test-coat-rewrite.glsl"), std::string::npos) << why;
    // the same id twice is refused
    files.push_back({"shaders/lib/models/builtin/09-again.glsl", read(extra)});
    EXPECT_THROW(make_model_registry(files), StackError);
}

// A file's table sets (`table:` lines) are laid out after the shipped files' in the files' order, as the build lays
// them out (STACK_TABLE_SET_LIST), and a `tables:` line reads them by name; a name no file declares is refused
TEST(ModelRegistry, ANewFilesTableSetsAreItsOwn) {
    const std::vector<BuiltinModelFile> shipped = source_files();
    const std::vector<ModelInfo> r0 = make_model_registry(shipped);
    // the shipped files' sets are the build's, bit by bit
    uint32_t k = 0;
    for (const ModelInfo& m : r0)
        for (const TableSetDeclaration& d : m.header.table_sets) {
            if (m.id != m.header.id) continue;   // a variant: its base's file
            ASSERT_NE(STACK_TABLE_SET_LIST[k].name, nullptr);
            EXPECT_EQ(d.name, STACK_TABLE_SET_LIST[k].name);
            EXPECT_EQ(d.floats, STACK_TABLE_SET_LIST[k].floats);
            EXPECT_EQ(m.shader_model, STACK_TABLE_SET_LIST[k].model);
            EXPECT_EQ(STACK_TABLE_SET_LIST[k].bit, 1u << k);
            ++k;
        }
    EXPECT_EQ(STACK_TABLE_SET_LIST[k].name, nullptr);
    EXPECT_EQ(find_model("openpbr")->header.tables, STACK_TABLES_COAT_ALBEDO | STACK_TABLES_OPENPBR_BASE_ALBEDO |
                                                        STACK_TABLES_OPENPBR_SEPARABLE |
                                                        STACK_TABLES_OPENPBR_LOBE_ALBEDO);
    const std::string extra = read(kSource + "/tests/builtin_models/99-test-coat-rewrite.glsl");
    auto with_header_lines = [&](const std::string& lines) {
        std::vector<BuiltinModelFile> files = shipped;
        std::string text = extra;
        text.insert(text.find("\n//\n") + 1, lines);
        files.push_back({"shaders/lib/models/builtin/99-test-coat-rewrite.glsl", text});
        return files;
    };
    // the new file's set (its `table:` line) is the next bit, another line the one after; `tables:` reads them
    const std::vector<ModelInfo> r = make_model_registry(
        with_header_lines("// table: test-set 4\n// tables: test-coat-rewrite-albedo, test-set, cycles-energy\n"));
    const ModelInfo& m = r[shipped.size()];
    ASSERT_EQ(m.header.table_sets.size(), 2u);
    EXPECT_EQ(m.header.table_sets[0].name, "test-coat-rewrite-albedo");
    EXPECT_EQ(m.header.table_sets[0].floats, 65u);
    EXPECT_EQ(m.header.table_sets[1].name, "test-set");
    EXPECT_EQ(m.header.tables, (1u << k) | (2u << k) | STACK_TABLES_CYCLES_ENERGY);
    try {
        make_model_registry(with_header_lines("// tables: cycle-energy\n"));
        ADD_FAILURE() << "an undeclared set accepted";
    } catch (const StackError& e) {
        EXPECT_NE(std::string(e.what()).find("tables: no built-in model file declares a table set 'cycle-energy'"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(make_model_registry(with_header_lines("// table: coat-albedo 65\n")), StackError);   // twice
}

// the built-in header: its own keys, an empty comment line ends it, each problem refused with its line
TEST(ModelRegistry, BuiltinHeadersAreCheckedAsUsersAre) {
    const std::string good = R"(// gonio-model: my-builtin
// citation: Doe 2027,
//   eq. 3
// summary: a coat
// stacks: one coat
// represents: coat-over-conductor
// reciprocal: no
// energy-conserving: no (the base is
//   not attenuated)
// variant: +g2+tir = convention g2, tir-below-media: with: both
// variant-energy-note: +g2+tir = measured
// variant-reciprocal: +g2+tir = yes
// tables: coat-albedo, cycles-energy
// family: tests
// artist-parameters: coat-over-conductor = base_color (colour),
//   Coat IOR
//
// the file's own description: key: not a key
GONIO_INLINE vec3 model_my_builtin(CoatParams p, uint terms, vec3 l, vec3 v) { return vec3(0.0f); }
)";
    const ModelFileHeader h = parse_model_header(good, "b.glsl", ModelFileKind::BuiltIn);
    EXPECT_EQ(h.citation, "Doe 2027, eq. 3");
    EXPECT_EQ(h.summary, "a coat");
    EXPECT_EQ(h.family, "tests");
    EXPECT_EQ(h.stacks, "one coat");
    EXPECT_EQ(h.energy_note, "the base is not attenuated");
    ASSERT_EQ(h.variants.size(), 1u);
    EXPECT_EQ(h.variants[0].suffix, "+g2+tir");
    EXPECT_EQ(h.variants[0].convention, MODEL_CONVENTION_G2 | MODEL_CONVENTION_TIR_BELOW_MEDIA);
    EXPECT_EQ(h.variants[0].what, "with: both");
    EXPECT_EQ(h.variants[0].energy_note, "measured");
    EXPECT_TRUE(h.variants[0].has_reciprocal);
    EXPECT_TRUE(h.variants[0].reciprocal);
    EXPECT_EQ(h.table_names, (std::vector<std::string>{"coat-albedo", "cycles-energy"}));
    EXPECT_EQ(h.tables_line, 13);
    EXPECT_EQ(builtin_model_entry("belcour18-forward+g2"), "model_belcour18_forward_g2");
    ASSERT_EQ(h.artist_parameters.size(), 1u);
    EXPECT_EQ(h.artist_parameters[0].shape, StackShape::CoatOverConductor);
    EXPECT_EQ(h.artist_parameters[0].line, 15);
    ASSERT_EQ(h.artist_parameters[0].names.size(), 2u);
    EXPECT_EQ(h.artist_parameters[0].names[0].name, "base_color");
    EXPECT_TRUE(h.artist_parameters[0].names[0].colour);
    EXPECT_EQ(h.artist_parameters[0].names[1].name, "Coat IOR");
    EXPECT_FALSE(h.artist_parameters[0].names[1].colour);
    auto refused = [&](const std::string& from, const std::string& to, const std::string& says) {
        std::string text = good;
        const size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
        try {
            parse_model_header(text, "b.glsl", ModelFileKind::BuiltIn);
            ADD_FAILURE() << "accepted:\n" << text;
        } catch (const StackError& e) { EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what(); }
    };
    refused("// summary: a coat\n", "", "b.glsl:1: the header has no 'summary:' line");
    refused("// stacks: one coat\n", "", "no 'stacks:' line");
    refused("// family: tests\n", "", "no 'family:' line");
    // a built-in states what it represents and claims (a user's file may leave these to gonio's measurement)
    refused("// represents: coat-over-conductor\n", "", "no 'represents:' line");
    refused("// reciprocal: no\n", "", "no 'reciprocal:' line");
    refused("convention g2, tir-below-media", "convention g3", "b.glsl:10: variant: unknown convention 'g3'");
    refused("+g2+tir = convention", "g2 = convention", "b.glsl:10: variant: expected '+SUFFIX");
    refused("// variant-energy-note: +g2+tir", "// variant-energy-note: +g2", "b.glsl:11: variant-energy-note: no");
    refused("// variant-reciprocal: +g2+tir", "// variant-reciprocal: +g2", "b.glsl:12: variant-reciprocal: no");
    refused("+g2+tir = yes", "+g2+tir = perhaps", "b.glsl:12: variant-reciprocal");
    refused("cycles-energy", "Cycles energy",
            "b.glsl:13: tables: expected table-set names, comma-separated; got 'Cycles energy'");
    refused("// family: tests\n", "// table: my-set\n// family: tests\n",
            "b.glsl:14: table: expected a set's name and its size in floats (table: NAME FLOATS); got 'my-set'");
    refused("// family: tests\n", "// table: my-set 0\n// family: tests\n", "b.glsl:14: table: expected");
    refused("model_my_builtin(", "model_f(", "defines no 'vec3 model_my_builtin(CoatParams p, uint terms");
    refused("// stacks:", "// stack:", "b.glsl:5: unknown header key 'stack:'");
    // artist parameters: for a shape it represents, each of them, once; names as the definition spells them
    refused("conductor = base_color", "lambertian = base_color",
            "b.glsl:15: artist-parameters: coat-over-lambertian is not among the shapes the model represents");
    refused("conductor = base_color", "any = base_color",
            "b.glsl:15: artist-parameters: expected coat-over-lambertian");
    refused("Coat IOR", "2nd IOR", "b.glsl:15: artist-parameters: expected a name");
    refused("// family: tests\n", "// artist-parameters: coat-over-conductor = x\n// family: tests\n",
            "b.glsl:16: artist-parameters: coat-over-conductor given twice (first at line 14)");
    refused("// represents: coat-over-conductor", "// represents: coat-over-conductor, coat-over-lambertian",
            "b.glsl:15: artist-parameters: no line for coat-over-lambertian, which the model represents");
    // a user's file takes none of the built-in keys
    EXPECT_THROW(parse_model_header("// gonio-model: u\n// summary: x\n// represents: any\n// reciprocal: no\n"
                                    "// energy-conserving: no\nvec3 model_f(vec3 l, vec3 v) { return l; }\n",
                                    "u.glsl"),
                 StackError);
}

}   // namespace

// A planned built-in's header and its refusals agree: on the shipped, hard and random stacks, every stack a model
// takes is one of the shapes its `represents:` names, and every stack it does not take is refused by one of its own
// `refuses:` lines (or its variant's convention), never by the shapes alone: what a model represents is said once, in
// its file, and the two ways of saying it cannot drift apart.
TEST(ModelRegistry, HeadersAndRefusalsAgree) {
    std::vector<Stack> stacks;
    for (const char* dir : {"stacks", "stacks/hard"})
        for (auto& e : std::filesystem::directory_iterator(kSource + "/" + dir))
            if (e.path().extension() == ".toml") stacks.push_back(parse_stack_file(e.path().string()));
    for (uint64_t i = 0; i < 300; ++i) stacks.push_back(random_stack(5, i));
    for (size_t m = 0; m < model_registry().size(); ++m) {
        const ModelInfo& info = model_registry()[m];
        if (info.header.plan == PlanKind::BlackBox) continue;
        int taken = 0, refused = 0;
        for (const Stack& s : stacks) {
            const std::string why = model_cannot_represent(m, s);
            bool shape = false;
            for (StackShape sh : info.header.represents) shape |= stack_has_shape(s, sh);
            if (why.empty()) {
                ++taken;
                EXPECT_TRUE(shape) << info.id << " takes " << s.name << ", none of the shapes it represents";
            } else {
                ++refused;
                EXPECT_EQ(why.find("this stack is none of them"), std::string::npos)
                    << info.id << " on " << s.name << ": refused by its shapes alone, not by its refuses: lines";
                EXPECT_EQ(why.find('{'), std::string::npos) << why;   // every placeholder filled
            }
        }
        EXPECT_GT(taken, 0) << info.id;
        EXPECT_GT(refused, 0) << info.id;
    }
}

// A model is one file: no file of host/ names a model (a string literal of a registry id, or of a variant of it), so
// that what is model-specific lives in the model's file (its header, its hooks) and a new model touches nothing
// else. The same search finds the ids the tests name (the check can fail).
TEST(ModelRegistry, NoHostFileNamesAModel) {
    auto named_in = [](const std::string& dir) {
        std::vector<std::string> found;
        for (const auto& e : std::filesystem::recursive_directory_iterator(kSource + "/" + dir)) {
            const std::string ext = e.path().extension().string();
            if (ext != ".cpp" && ext != ".h") continue;
            const std::string text = read(e.path());
            for (const ModelInfo& m : model_registry())
                if (text.find('"' + m.id + '"') != std::string::npos ||
                    text.find('"' + m.id + '+') != std::string::npos)
                    found.push_back(std::filesystem::relative(e.path(), kSource).string() + ": " + m.id);
        }
        return found;
    };
    const std::vector<std::string> in_host = named_in("host");
    std::string list;
    for (const std::string& f : in_host) list += "\n  " + f;
    EXPECT_TRUE(in_host.empty()) << "host/ names models:" << list;
    EXPECT_FALSE(named_in("tests").empty());
}
