#include "model_registry.h"

#include "model_plan.h"
#include "model_twin.h"
#include "shader_sources.h"

#include <algorithm>

static_assert(gonio::MODEL_CONVENTION_G2 == CONVENTION_G2 &&
              gonio::MODEL_CONVENTION_TIR_BELOW_MEDIA == CONVENTION_TIR_BELOW_MEDIA &&
              gonio::MODEL_CONVENTION_DARKENING_T2 == CONVENTION_DARKENING_T2 &&
              gonio::MODEL_CONVENTION_ROUGHENING_PR261 == CONVENTION_ROUGHENING_PR261 &&
              gonio::MODEL_CONVENTION_REFLECTANCE_FRESNEL == CONVENTION_REFLECTANCE_FRESNEL &&
              gonio::MODEL_CONVENTION_MATERIALX_GRAPH == CONVENTION_MATERIALX_GRAPH &&
              gonio::MODEL_CONVENTION_COAT_FRESNEL_VH == CONVENTION_COAT_FRESNEL_VH &&
              gonio::MODEL_CONVENTION_CYCLES_4_4 == CONVENTION_CYCLES_4_4 &&
              gonio::MODEL_CONVENTION_RECIPROCAL_COAT == CONVENTION_RECIPROCAL_COAT &&
              gonio::MODEL_CONVENTION_SEPARABLE_G == CONVENTION_SEPARABLE_G &&
              gonio::MODEL_CONVENTION_DARKENING_NUMERATOR == CONVENTION_DARKENING_NUMERATOR &&
              gonio::MODEL_CONVENTION_SINGLE_SCATTERING_LOBES == CONVENTION_SINGLE_SCATTERING_LOBES);
static_assert(gonio::kModelMaxParameters == MODEL_MAX_PARAMETERS, "the models' parameters, host and shaders");
namespace gonio {

std::vector<BuiltinModelFile> builtin_model_files() {
    static const std::string prefix = "gonio/lib/models/builtin/", suffix = ".glsl";
    std::vector<BuiltinModelFile> files;
    for (const EmbeddedSource& e : embedded_shader_sources()) {
        const std::string name = e.name;
        if (name.rfind(prefix, 0) != 0 || name.size() <= prefix.size() + suffix.size() ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0 ||
            name.find('/', prefix.size()) != std::string::npos)
            continue;
        files.push_back({"shaders/" + name.substr(6), e.text});
    }
    // the order of CMakeLists.txt's list(SORT) of the same folder: the codes of the SPIR-V modules
    std::sort(files.begin(), files.end(),
              [](const BuiltinModelFile& a, const BuiltinModelFile& b) { return a.path < b.path; });
    return files;
}

namespace {

// The table sets the files declare (`table:` lines), each a bit in the files' order as cmake/builtin_models.cmake
// lays them out; and each file's `tables:` names as those bits (a name no file declares is refused at its line)
void resolve_table_sets(std::vector<ModelInfo>& r) {
    std::vector<std::pair<std::string, uint32_t>> bits;
    for (const ModelInfo& m : r)
        for (const TableSetDeclaration& d : m.header.table_sets) {
            for (const auto& [name, bit] : bits)
                if (name == d.name) throw StackError(m.file, d.line, "table: '" + d.name + "' is declared twice");
            if (bits.size() == 32) throw StackError(m.file, d.line, "table: more than 32 table sets");
            bits.push_back({d.name, 1u << bits.size()});
        }
    for (ModelInfo& m : r)
        for (const std::string& name : m.header.table_names) {
            uint32_t bit = 0;
            std::string known;
            for (const auto& [n, b] : bits) {
                if (n == name) bit = b;
                known += (known.empty() ? "" : ", ") + n;
            }
            if (!bit)
                throw StackError(
                    m.file, m.header.tables_line,
                    "tables: no built-in model file declares a table set '" + name + "' (declared: " + known + ")");
            m.header.tables |= bit;
        }
}

// The layout the build generated from the same files (builtin_models.glsl STACK_TABLE_SET_LIST): the same sets, in
// the same order, of the same sizes, or the binary's files and its shaders disagree
void check_generated_table_layout(const std::vector<ModelInfo>& r) {
    size_t k = 0;
    for (const ModelInfo& m : r)
        for (const TableSetDeclaration& d : m.header.table_sets) {
            if (m.id != m.header.id) continue;   // a variant: its file's sets are its base's
            const StackTableSetInfo& g = STACK_TABLE_SET_LIST[k++];
            if (!g.name || d.name != g.name || d.floats != g.floats || m.shader_model != g.model)
                throw std::logic_error(m.file + ":" + std::to_string(d.line) + ": table set '" + d.name + "' (" +
                                       std::to_string(d.floats) + " floats) is not the build's (builtin_models.glsl: " +
                                       (g.name ? g.name : "none") + ", " + std::to_string(g.floats) +
                                       " floats): rebuild");
        }
    if (STACK_TABLE_SET_LIST[k].name) throw std::logic_error("the build lays out table sets no file declares: rebuild");
}

}   // namespace

std::vector<ModelInfo> make_model_registry(const std::vector<BuiltinModelFile>& files) {
    std::vector<ModelInfo> r;
    for (const BuiltinModelFile& f : files) {
        ModelInfo m;
        m.header = parse_model_header(f.text, f.path, ModelFileKind::BuiltIn);
        for (const ModelInfo& o : r)
            if (o.id == m.header.id)
                throw StackError(f.path, 1, "gonio-model: '" + m.header.id + "' is also " + o.file + "'s id");
        m.id = m.header.id;
        m.citation = m.header.citation;
        m.summary = m.header.summary;
        m.represents = m.header.stacks;
        m.reciprocal = m.header.reciprocal;
        m.energy_conserving = m.header.energy_conserving;
        m.energy_note = m.header.energy_note;
        m.shader_model = uint32_t(r.size());   // the file's place: its SPIR-V modules and eval_model's code
        m.file = f.path;
        r.push_back(m);
    }
    resolve_table_sets(r);
    // the variants of the same code (docs/MODELS.md, "Conventions"): the authors' other readings (OpenPBR's
    // +dev1.2, +pr261, +materialx, Standard Surface's +osl), and gonio's alternatives to the official codes' conventions: +g2,
    // the reference's height-correlated G2 in the GGX lobes and in the FGD/TIR tables instead of
    // the separable G1(l) G1(v); +tir (Belcour's adding loop only), the TIR term of an interface kept when an
    // absorbing medium lies under it; +g2+tir, both
    const size_t bases = r.size();
    for (size_t i = 0; i < bases; ++i) {
        const ModelInfo base = r[i];   // a copy: r grows below
        for (const ModelVariant& v : base.header.variants) {
            ModelInfo m = base;
            m.id += v.suffix;
            // gonio's own alternatives (g2, tir-below-media), or another reading the model's authors published
            // (OpenPBR's drafts, Standard Surface's OSL reference), which the variant's summary names
            bool gonios = false;
            for (const ModelConvention& c : model_conventions()) gonios |= c.gonios && (v.convention & c.bit) != 0;
            m.citation = (gonios ? "gonio's variant of " : "a variant of ") + base.id + " (" + base.citation + ")";
            m.summary = "as " + base.id + ", " + v.what;
            m.convention = v.convention;
            // the energy excess measured for this variant on the hard cases (tests/test_hard_cases.cpp)
            if (v.has_energy_note) m.energy_note = v.energy_note;
            if (v.has_reciprocal) m.reciprocal = v.reciprocal;
            for (const ModelInfo& o : r)
                if (o.id == m.id) throw StackError(m.file, 1, "variant: " + m.id + " is also " + o.file + "'s id");
            r.push_back(m);
        }
    }
    return r;
}

const std::vector<ModelInfo>& model_registry() {
    static const std::vector<ModelInfo> r = [] {
        std::vector<ModelInfo> r = make_model_registry(builtin_model_files());
        check_generated_table_layout(r);
        return r;
    }();
    return r;
}

const ModelInfo* find_model(const std::string& id) {
    for (const ModelInfo& m : model_registry())
        if (m.id == id) return &m;
    return nullptr;
}

const std::string& code_id(uint32_t code) { return model_registry().at(code).id; }

uint32_t shader_model_of(size_t index) { return model_registry().at(index).shader_model; }
bool uses_tables(size_t index) {
    const PlanKind k = model_registry().at(index).header.plan;
    return k == PlanKind::Lobes || k == PlanKind::LobesSymmetric;
}

std::string model_not_selected(size_t index, const ModelOptions& o) {
    return model_id_not_selected(model_registry().at(index).id, o);
}

std::string model_id_not_selected(const std::string& id, const ModelOptions& o) {
    if (o.selected.empty()) {
        if (o.variants) return "";
        for (const ModelInfo& m : model_registry())
            if (m.id == id && m.convention != 0)
                return id + " not selected (a variant: --models all runs the variants too, --models " + id +
                       " this one)";
        return "";
    }
    if (std::find(o.selected.begin(), o.selected.end(), id) != o.selected.end()) return "";
    std::string list;
    for (const std::string& s : o.selected) list += (list.empty() ? "" : ",") + s;
    return id + " not selected (--models " + list + ")";
}

}   // namespace gonio
