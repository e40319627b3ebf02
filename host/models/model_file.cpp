// model_file.cpp: the header of a model file (model_file.h).
#include "model_file.h"
#include "input_file.h"
#include "text_format.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

namespace gonio {

namespace {

struct ShapeName {
    StackShape shape;
    const char* name;
};
constexpr ShapeName kShapes[] = {
    {StackShape::Any, "any"},
    {StackShape::CoatOverLambertian, "coat-over-lambertian"},
    {StackShape::CoatOverConductor, "coat-over-conductor"},
    {StackShape::CoatOverDielectricOverLambertian, "coat-over-dielectric-over-lambertian"},
    {StackShape::DielectricsOverLambertian, "dielectric-stack-over-lambertian"},
    {StackShape::DielectricsOverConductor, "dielectric-stack-over-conductor"},
    {StackShape::Slab, "slab"},
    {StackShape::Transmissive, "transmissive"},
    {StackShape::FibresOverLambertian, "fibres-over-lambertian"},
};

std::string shape_list() {
    std::string s;
    for (const auto& k : kShapes) s += std::string(s.empty() ? "" : ", ") + k.name;
    return s;
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

bool dielectrics_over(const Stack& s, InterfaceKind base) {
    if (s.layers.empty() || s.base().kind != base) return false;
    for (size_t i = 0; i + 1 < s.layers.size(); ++i)
        if (s.layers[i].kind != InterfaceKind::Dielectric) return false;
    return true;
}

// yes / no, then an optional "(reason)"
bool parse_yes_no(const std::string& value, const std::string& key, const std::string& path, int line,
                  std::string* note) {
    static const std::regex form(R"(^(yes|no)\s*(\((.*)\))?\s*$)");
    std::smatch m;
    if (!std::regex_match(value, m, form))
        throw StackError(path, line,
                         key + ": expected yes or no, optionally followed by (a reason), got '" + value + "'");
    if (note) *note = m[3].str();
    return m[1] == "yes";
}

}   // namespace

const char* to_string(StackShape s) {
    for (const auto& k : kShapes)
        if (k.shape == s) return k.name;
    return "?";
}

bool stack_has_shape(const Stack& s, StackShape shape) {
    switch (shape) {
        case StackShape::Any:
            return true;
        case StackShape::CoatOverLambertian:
            return s.layers.size() == 2 && dielectrics_over(s, InterfaceKind::Lambertian);
        case StackShape::CoatOverConductor:
            return s.layers.size() == 2 && dielectrics_over(s, InterfaceKind::Conductor);
        case StackShape::CoatOverDielectricOverLambertian:
            return s.layers.size() == 3 && dielectrics_over(s, InterfaceKind::Lambertian);
        case StackShape::DielectricsOverLambertian:
            return dielectrics_over(s, InterfaceKind::Lambertian);
        case StackShape::DielectricsOverConductor:
            return dielectrics_over(s, InterfaceKind::Conductor);
        case StackShape::Transmissive:
            return s.transmissive() && dielectrics_over(s, InterfaceKind::Dielectric);
        case StackShape::Slab:
            return s.transmissive() && dielectrics_over(s, InterfaceKind::Dielectric) &&
                   s.base().ior == glm::vec3(s.exterior_ior);
        case StackShape::FibresOverLambertian:
            return s.layers.size() == 2 && dielectrics_over(s, InterfaceKind::Lambertian) &&
                   s.layers[0].ior == glm::vec3(s.exterior_ior) && s.layers[0].roughness == 0.0f &&
                   s.medium_scatters(0) && s.layers[0].phase == MediumPhase::SggxFibre;
    }
    return false;   // a shape without a rule here matches no stack
}

std::string builtin_model_entry(const std::string& id) {
    std::string name = "model_";
    for (char c : id) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return name;
}

const std::vector<ModelConvention>& model_conventions() {
    static const std::vector<ModelConvention> all = {
        {"g2", MODEL_CONVENTION_G2, true},
        {"tir-below-media", MODEL_CONVENTION_TIR_BELOW_MEDIA, true},
        {"darkening-t2", MODEL_CONVENTION_DARKENING_T2, false},
        {"roughening-pr261", MODEL_CONVENTION_ROUGHENING_PR261, false},
        {"reflectance-fresnel", MODEL_CONVENTION_REFLECTANCE_FRESNEL, false},
        {"materialx-graph", MODEL_CONVENTION_MATERIALX_GRAPH, false},
        {"coat-fresnel-vh", MODEL_CONVENTION_COAT_FRESNEL_VH, false},
        {"cycles-4.4", MODEL_CONVENTION_CYCLES_4_4, false},
        {"reciprocal-coat", MODEL_CONVENTION_RECIPROCAL_COAT, false},
        {"separable-g", MODEL_CONVENTION_SEPARABLE_G, false},
        {"darkening-numerator", MODEL_CONVENTION_DARKENING_NUMERATOR, false},
        {"single-scattering-lobes", MODEL_CONVENTION_SINGLE_SCATTERING_LOBES, false},
    };
    return all;
}

namespace {

constexpr struct {
    PlanKind kind;
    const char* name;
} kPlans[] = {{PlanKind::BlackBox, "black-box"},
              {PlanKind::Coat, "coat"},
              {PlanKind::CoatRefracted, "coat-refracted"},
              {PlanKind::Lobes, "lobes"},
              {PlanKind::LobesSymmetric, "lobes-symmetric"}};

constexpr struct {
    StackCondition when;
    const char* name;
} kConditions[] = {{StackCondition::ScatteringMedium, "scattering-medium"},
                   {StackCondition::BackwardScatteringMedium, "backward-scattering-medium"},
                   {StackCondition::LambertianBase, "lambertian-base"},
                   {StackCondition::Transmissive, "transmissive"},
                   {StackCondition::SubstrateNotExterior, "substrate-not-exterior"},
                   {StackCondition::BaseNotLambertianOrConductor, "base-not-lambertian-or-conductor"},
                   {StackCondition::BaseNotLambertian, "base-not-lambertian"},
                   {StackCondition::NotTwoLayers, "not-two-layers"},
                   {StackCondition::AbsorbingMedium, "absorbing-medium"},
                   {StackCondition::CoatIorNot1_5, "coat-ior-not-1.5"},
                   {StackCondition::CoatIorBeyond3, "coat-ior-beyond-3"},
                   {StackCondition::CoatIorBelow1, "coat-ior-below-1"},
                   {StackCondition::AbsorbingBaseMedium, "absorbing-base-medium"},
                   {StackCondition::NotCoatOverBase, "not-coat-over-base"},
                   {StackCondition::FibreDepthNot1, "fibre-depth-not-1"}};

template <class Table>
std::string names_of(const Table& t) {
    std::string s;
    for (const auto& k : t) s += std::string(s.empty() ? "" : ", ") + k.name;
    return s;
}

// The header's lines "key: value", each with the comment lines that continue it: a user's file continues its
// citation only (a comment line after another key is the file's own), a built-in's every key up to an empty
// comment line. A line indented by two spaces or more after its "//" is never a key ("//   complement: ..."
// continues the line above it; "// complement: ..." would be a key).
struct HeaderEntry {
    std::string key, value;
    int line;
};
// The longest header line and key value read (a header is data from outside; the patterns below run on them)
constexpr size_t kMaxHeaderLine = 1000, kMaxHeaderValue = 8000;

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool space_char(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Whether text defines   RET NAME(T1 a, T2 b, ...)   (parameter types `types`, any whitespace between tokens): a
// linear scan, where std::regex recurses once per character matched and overflows the stack on a long run of spaces
bool defines_function(const std::string& text, const std::string& ret, const std::string& name,
                      const std::vector<std::string>& types) {
    auto skip = [&](size_t i) {
        while (i < text.size() && space_char(text[i])) ++i;
        return i;
    };
    auto word_at = [&](size_t i, const std::string& w) {   // w at i, a whole word
        return text.compare(i, w.size(), w) == 0 &&
               (i + w.size() == text.size() || !identifier_char(text[i + w.size()]));
    };
    for (size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
        if ((at > 0 && identifier_char(text[at - 1])) || !word_at(at, name)) continue;
        size_t b = at;   // RET and at least one space before NAME
        while (b > 0 && space_char(text[b - 1])) --b;
        if (b == at || b < ret.size() || text.compare(b - ret.size(), ret.size(), ret) != 0) continue;
        if (b > ret.size() && identifier_char(text[b - ret.size() - 1])) continue;
        size_t i = skip(at + name.size());
        if (i >= text.size() || text[i] != '(') continue;
        bool ok = true;
        for (size_t k = 0; k < types.size() && ok; ++k) {
            i = skip(i + 1);   // after '(' or ','
            if (!word_at(i, types[k])) {
                ok = false;
                break;
            }
            const size_t id = skip(i + types[k].size());
            size_t e = id;
            while (e < text.size() && identifier_char(text[e])) ++e;
            if (id == i + types[k].size() || e == id) {   // a space, then the parameter's name
                ok = false;
                break;
            }
            i = skip(e);
            ok = i < text.size() && text[i] == (k + 1 == types.size() ? ')' : ',');
        }
        if (ok) return true;
    }
    return false;
}

// Whether a line of text starts (after spaces or tabs) with   uint model_lobes(   (a definition, not a mention in a
// comment)
bool defines_lobe_hints(const std::string& text) {
    const std::string name = "model_lobes";
    for (size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
        size_t b = at;
        while (b > 0 && (text[b - 1] == ' ' || text[b - 1] == '\t')) --b;
        if (b == at || b < 4 || text.compare(b - 4, 4, "uint") != 0) continue;
        size_t s = b - 4;
        while (s > 0 && (text[s - 1] == ' ' || text[s - 1] == '\t')) --s;
        if (s > 0 && text[s - 1] != '\n') continue;
        size_t e = at + name.size();
        while (e < text.size() && (text[e] == ' ' || text[e] == '\t')) ++e;
        if (e < text.size() && text[e] == '(') return true;
    }
    return false;
}
std::vector<HeaderEntry> header_entries(const std::string& text, const std::string& path, bool builtin, int& id_line) {
    static const std::regex key_line(R"(^([a-z][a-z-]*):\s*(.*)$)");
    std::istringstream in(text);
    std::string raw;
    std::vector<HeaderEntry> entries;
    int line = 0;
    bool continues = false;
    id_line = 0;
    while (std::getline(in, raw)) {
        ++line;
        const std::string t = trim(raw);
        if (t.empty() && !id_line) continue;   // blank lines before the header
        if (t.rfind("//", 0) != 0) break;   // the header ends at the first line that is not a comment
        if (raw.size() > kMaxHeaderLine)   // bounded before any pattern is matched (std::regex recurses per character)
            throw StackError(path, line,
                             "a header line of " + std::to_string(raw.size()) + " characters (at most " +
                                 std::to_string(kMaxHeaderLine) + ")");
        const std::string body = trim(t.substr(2));
        if (builtin && body.empty() && id_line) break;   // a built-in's header ends at an empty comment line
        const bool indented = t.compare(2, 2, "  ") == 0;
        std::smatch m;
        if ((indented && id_line) || !std::regex_match(body, m, key_line)) {
            if (!id_line)
                throw StackError(path, line, "expected the model's header to start with '// gonio-model: ID'");
            if (continues && !body.empty()) entries.back().value += " " + body;
            if (continues && entries.back().value.size() > kMaxHeaderValue)
                throw StackError(
                    path, line,
                    entries.back().key + ": its value runs over " + std::to_string(kMaxHeaderValue) + " characters");
            continue;
        }
        const std::string key = m[1], value = trim(m[2]);
        if (!id_line && key != "gonio-model")
            throw StackError(path, line,
                             "expected the model's header to start with '// gonio-model: ID', got '" + key + ":'");
        if (key == "gonio-model") {
            if (id_line)
                throw StackError(path, line,
                                 "gonio-model: given twice (first on line " + std::to_string(id_line) + ")");
            id_line = line;
        }
        entries.push_back({key, value, line});
        continues = builtin ? key != "gonio-model" : key == "citation";
    }
    if (!id_line) throw StackError(path, 1, "expected the model's header to start with '// gonio-model: ID'");
    return entries;
}

void read_represents(ModelFileHeader& h, const HeaderEntry& e) {
    std::istringstream list(e.value);
    std::string item;
    while (std::getline(list, item, ',')) {
        item = trim(item);
        bool found = false;
        for (const auto& k : kShapes)
            if (item == k.name) h.represents.push_back(k.shape), found = true;
        if (!found)
            throw StackError(h.path, e.line,
                             "represents: unknown stack shape '" + item +
                                 "' (expected a comma-separated list of: " + shape_list() + ")");
    }
    if (h.represents.empty()) throw StackError(h.path, e.line, "represents: expected at least one of: " + shape_list());
}

std::string convention_list() {
    std::string out;
    for (const ModelConvention& c : model_conventions()) out += (out.empty() ? "" : ", ") + std::string(c.name);
    return out;
}

// variant: +SUFFIX = convention NAME[, NAME]: what it does differently
void read_variant(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex form(R"(^(\S+)\s*=\s*convention\s+([a-z0-9., -]+?)\s*:\s*(.+)$)");
    static const std::regex suffix_form(R"(^(\+[a-z0-9][a-z0-9._-]*)+$)");   // "+g2", "+g2+tir"
    std::smatch m;
    if (!std::regex_match(e.value, m, form) || !std::regex_match(m[1].str(), suffix_form))
        throw StackError(h.path, e.line,
                         "variant: expected '+SUFFIX = convention NAME[, NAME]: what it does differently' "
                         "(conventions " +
                             convention_list() + "), got '" + e.value + "'");
    ModelVariant v;
    v.suffix = m[1];
    v.what = m[3];
    std::istringstream list(m[2].str());
    std::string name;
    while (std::getline(list, name, ',')) {
        name = trim(name);
        const auto& all = model_conventions();
        auto c = std::find_if(all.begin(), all.end(), [&](const ModelConvention& k) { return name == k.name; });
        if (c == all.end())
            throw StackError(h.path, e.line,
                             "variant: unknown convention '" + name + "' (expected " + convention_list() + ")");
        v.convention |= c->bit;
    }
    for (const ModelVariant& w : h.variants)
        if (w.suffix == v.suffix) throw StackError(h.path, e.line, "variant: " + v.suffix + " given twice");
    h.variants.push_back(v);
}

void read_variant_energy_note(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex form(R"(^(\S+)\s*=\s*(.+)$)");
    std::smatch m;
    if (!std::regex_match(e.value, m, form))
        throw StackError(h.path, e.line, "variant-energy-note: expected '+SUFFIX = the note', got '" + e.value + "'");
    for (ModelVariant& v : h.variants)
        if (v.suffix == m[1]) {
            v.energy_note = m[2];
            v.has_energy_note = true;
            return;
        }
    throw StackError(h.path, e.line, e.key + ": no 'variant: " + m[1].str() + " = ...' line before it");
}

// variant-reciprocal: +SUFFIX = yes | no
void read_variant_reciprocal(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex form(R"(^(\S+)\s*=\s*(.+)$)");
    std::smatch m;
    if (!std::regex_match(e.value, m, form))
        throw StackError(h.path, e.line, "variant-reciprocal: expected '+SUFFIX = yes' or 'no', got '" + e.value + "'");
    for (ModelVariant& v : h.variants)
        if (v.suffix == m[1]) {
            v.reciprocal = parse_yes_no(m[2], e.key, h.path, e.line, nullptr);
            v.has_reciprocal = true;
            return;
        }
    throw StackError(h.path, e.line, e.key + ": no 'variant: " + m[1].str() + " = ...' line before it");
}

void read_plan(ModelFileHeader& h, const HeaderEntry& e) {
    for (const auto& k : kPlans)
        if (e.value == k.name) {
            h.plan = k.kind;
            return;
        }
    throw StackError(h.path, e.line, "plan: expected one of " + names_of(kPlans) + ", got '" + e.value + "'");
}

// tables: NAME[, NAME...] (the registry resolves the names against the files' `table:` lines)
void read_tables(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex name(R"(^[a-z0-9-]+$)");
    std::stringstream items(e.value);
    std::string item;
    while (std::getline(items, item, ',')) {
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (!std::regex_match(item, name))
            throw StackError(h.path, e.line, "tables: expected table-set names, comma-separated; got '" + item + "'");
        h.table_names.push_back(item);
    }
    h.tables_line = e.line;
}

// table: NAME FLOATS
void read_table_set(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex form(R"(^([a-z0-9-]+)\s+([0-9]{1,6})$)");
    std::smatch m;
    if (!std::regex_match(e.value, m, form) || std::stoul(m[2]) == 0)
        throw StackError(
            h.path, e.line,
            "table: expected a set's name and its size in floats (table: NAME FLOATS); got '" + e.value + "'");
    h.table_sets.push_back({m[1], uint32_t(std::stoul(m[2])), e.line});
}

// refuses: CONDITION = REASON
void read_refusal(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex form(R"(^([a-z0-9.-]+)\s*=\s*(.+)$)");
    std::smatch m;
    if (std::regex_match(e.value, m, form))
        for (const auto& k : kConditions)
            if (m[1] == k.name) {
                h.refuses.push_back({k.when, m[2], e.line});
                return;
            }
    throw StackError(h.path, e.line,
                     "refuses: expected 'CONDITION = the reason' with a condition of " + names_of(kConditions) +
                         ", got '" + e.value + "'");
}

// parameter: NAME default VALUE range [A, B] -- meaning (the meaning optional)
void read_parameter(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::string num = R"(([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))";
    static const std::regex form("^([a-z][a-z0-9_]{0,31})\\s+default\\s+" + num + "\\s+range\\s+\\[\\s*" + num +
                                 "\\s*,\\s*" + num + "\\s*\\](?:\\s+--\\s+(.+))?$");
    std::smatch m;
    if (!std::regex_match(e.value, m, form))
        throw StackError(h.path, e.line,
                         "parameter: expected 'NAME default VALUE range [A, B] -- what it means' (NAME: lower-case "
                         "letters, digits and _), got '" +
                             e.value + "'");
    ModelParameter p{m[1], std::stod(m[2]), std::stod(m[3]), std::stod(m[4]), m[5], e.line};
    if (!(p.lo < p.hi) || !(p.value >= p.lo && p.value <= p.hi))
        throw StackError(h.path, e.line,
                         "parameter " + p.name + ": expected A < B and the default within [A, B], got default " +
                             m[2].str() + " range [" + m[3].str() + ", " + m[4].str() + "]");
    for (const ModelParameter& q : h.parameters)
        if (q.name == p.name)
            throw StackError(h.path, e.line,
                             "parameter " + p.name + ": given twice (first at line " + std::to_string(q.line) + ")");
    if (h.parameters.size() == kModelMaxParameters)
        throw StackError(
            h.path, e.line,
            "parameter " + p.name + ": a model has at most " + std::to_string(kModelMaxParameters) + " parameters");
    h.parameters.push_back(p);
}

// artist-parameters: SHAPE = NAME, NAME (colour), ...
void read_artist_parameters(ModelFileHeader& h, const HeaderEntry& e) {
    static const std::regex form(R"(^([a-z-]+)\s*=\s*(.+)$)");
    static const std::regex name_form(R"(^([A-Za-z][A-Za-z0-9_. ]*?)(\s*\(colour\))?$)");
    std::smatch m;
    if (!std::regex_match(e.value, m, form))
        throw StackError(h.path, e.line,
                         "artist-parameters: expected 'SHAPE = NAME, NAME (colour), ...', got '" + e.value + "'");
    ArtistParameterList list;
    list.line = e.line;
    const std::string shape = m[1];
    bool found = false;
    for (const auto& k : kShapes)
        if (shape == k.name) list.shape = k.shape, found = true;
    const bool mapped = list.shape == StackShape::CoatOverLambertian || list.shape == StackShape::CoatOverConductor ||
                        list.shape == StackShape::CoatOverDielectricOverLambertian ||
                        list.shape == StackShape::FibresOverLambertian;
    if (!found || !mapped)
        throw StackError(h.path, e.line,
                         "artist-parameters: expected coat-over-lambertian, coat-over-conductor, "
                         "coat-over-dielectric-over-lambertian or fibres-over-lambertian before '=', got '" +
                             shape + "'");
    for (const ArtistParameterList& other : h.artist_parameters)
        if (other.shape == list.shape)
            throw StackError(
                h.path, e.line,
                "artist-parameters: " + shape + " given twice (first at line " + std::to_string(other.line) + ")");
    std::istringstream names(m[2].str());
    std::string item;
    while (std::getline(names, item, ',')) {
        item = trim(item);
        std::smatch n;
        if (!std::regex_match(item, n, name_form))
            throw StackError(h.path, e.line,
                             "artist-parameters: expected a name (a letter, then letters, digits, _ . or spaces) with "
                             "an optional ' (colour)', got '" +
                                 item + "'");
        list.names.push_back({n[1], n[2].matched});
    }
    if (list.names.size() > kModelMaxArtistParameters)
        throw StackError(h.path, e.line,
                         "artist-parameters: at most " + std::to_string(kModelMaxArtistParameters) +
                             " per shape (MODEL_MAX_ARTIST_PARAMETERS), got " + std::to_string(list.names.size()));
    h.artist_parameters.push_back(list);
}

// A model's artist parameters are for the shapes it represents, each of them (of the three a mapping takes)
void check_artist_parameters(const ModelFileHeader& h) {
    if (h.artist_parameters.empty()) return;
    auto represents = [&](StackShape s) {
        return std::find(h.represents.begin(), h.represents.end(), s) != h.represents.end();
    };
    for (const ArtistParameterList& list : h.artist_parameters)
        if (!represents(list.shape))
            throw StackError(h.path, list.line,
                             std::string("artist-parameters: ") + to_string(list.shape) +
                                 " is not among the shapes the model represents (represents:)");
    for (StackShape s : h.represents) {
        if (s != StackShape::CoatOverLambertian && s != StackShape::CoatOverConductor &&
            s != StackShape::CoatOverDielectricOverLambertian)
            continue;
        bool named = false;
        for (const ArtistParameterList& list : h.artist_parameters) named |= list.shape == s;
        if (!named)
            throw StackError(
                h.path, h.artist_parameters.front().line,
                std::string("artist-parameters: no line for ") + to_string(s) + ", which the model represents");
    }
}

// One "key: value" of the header into h; `seen` collects the keys given.
void read_entry(ModelFileHeader& h, const HeaderEntry& e, bool builtin, std::vector<std::string>& seen) {
    const std::string& key = e.key;
    seen.push_back(key);
    if (key == "gonio-model") {
        static const std::regex id_form(R"(^[a-z0-9][a-z0-9._+-]{0,63}$)");
        if (!std::regex_match(e.value, id_form))
            throw StackError(
                h.path, e.line,
                "gonio-model: expected an id of lower-case letters, digits and . _ + - (at most 64), got '" + e.value +
                    "'");
        if (e.value == "reference")
            throw StackError(h.path, e.line,
                             "gonio-model: 'reference' names the reference in every output; give the model another id");
        h.id = e.value;
    } else if (key == "citation") {
        h.citation = e.value;
    } else if (key == "represents") {
        read_represents(h, e);
    } else if (key == "reciprocal") {
        h.reciprocal = parse_yes_no(e.value, key, h.path, e.line, nullptr);
        h.states_reciprocity = true;
    } else if (key == "energy-conserving") {
        h.energy_conserving = parse_yes_no(e.value, key, h.path, e.line, &h.energy_note);
        h.states_energy = true;
    } else if (key == "parameter") {
        read_parameter(h, e);
    } else if (builtin && key == "summary") {
        h.summary = e.value;
    } else if (builtin && key == "family") {
        h.family = e.value;
    } else if (builtin && key == "stacks") {
        h.stacks = e.value;
    } else if (builtin && key == "mapping") {
        h.mapping = e.value;
    } else if (builtin && key == "artist-parameters") {
        read_artist_parameters(h, e);
    } else if (builtin && key == "variant") {
        read_variant(h, e);
    } else if (builtin && key == "variant-energy-note") {
        read_variant_energy_note(h, e);
    } else if (builtin && key == "variant-reciprocal") {
        read_variant_reciprocal(h, e);
    } else if (builtin && key == "plan") {
        read_plan(h, e);
    } else if (builtin && key == "refuses") {
        read_refusal(h, e);
    } else if (builtin && key == "tables") {
        read_tables(h, e);
    } else if (builtin && key == "table") {
        read_table_set(h, e);
    } else {
        throw StackError(
            h.path, e.line,
            "unknown header key '" + key +
                (builtin
                     ? ":' (expected gonio-model, citation, summary, family, stacks, mapping, artist-parameters, "
                       "represents, "
                       "reciprocal, energy-conserving, parameter, variant, variant-energy-note, variant-reciprocal, "
                       "plan, table, tables, refuses)"
                     : ":' (expected gonio-model, citation, represents, reciprocal, energy-conserving, parameter)"));
    }
}

// The file defines its entry: model_f(l, v) for a user's, model_ID(p, terms, l, v) for a built-in.
void check_entry(ModelFileHeader& h, const std::string& text, bool builtin, int id_line) {
    if (builtin) {
        const std::string entry = builtin_model_entry(h.id);
        if (!defines_function(text, "vec3", entry, {"CoatParams", "uint", "vec3", "vec3"}))
            throw StackError(h.path, id_line,
                             "the file defines no 'vec3 " + entry +
                                 "(CoatParams p, uint terms, vec3 l, vec3 v)' (a built-in model's entry: its terms' "
                                 "f in 1/sr, cosine excluded, directions away from the surface)");
        return;
    }
    if (!defines_function(text, "vec3", "model_f", {"vec3", "vec3"}))
        throw StackError(h.path, id_line,
                         "the file defines no 'vec3 model_f(vec3 l, vec3 v)' (the model's f in 1/sr, cosine excluded, "
                         "directions away from the surface)");
    h.has_lobe_hints = defines_lobe_hints(text);   // models/user_model.glsl, "lobe hints"
}

}   // namespace

const char* to_string(PlanKind k) {
    for (const auto& p : kPlans)
        if (p.kind == k) return p.name;
    return "?";
}

ModelFileHeader parse_model_header(const std::string& text, const std::string& path, ModelFileKind kind) {
    const bool builtin = kind == ModelFileKind::BuiltIn;
    ModelFileHeader h;
    h.path = path;
    int id_line = 0;
    std::vector<std::string> seen;
    for (const HeaderEntry& e : header_entries(text, path, builtin, id_line)) read_entry(h, e, builtin, seen);
    auto require = [&](const char* key, const char* what) {
        if (std::find(seen.begin(), seen.end(), key) == seen.end())
            throw StackError(path, id_line, std::string("the header has no '") + key + ":' line (" + what + ")");
    };
    // a built-in says what it represents and claims; a user's file may leave it to gonio to measure
    if (builtin) {
        require("represents", "which stacks the model represents");
        require("reciprocal", "yes or no");
        require("energy-conserving", "yes or no");
    } else if (h.represents.empty()) {
        h.represents = {StackShape::Any};
    }
    if (builtin) require("summary", "what the model does, in one line");
    if (builtin) require("family", "the family it is grouped with in reports");
    if (builtin) require("stacks", "which stacks it represents, in words");
    check_artist_parameters(h);
    check_entry(h, text, builtin, id_line);
    return h;
}

ModelFileHeader read_model_file(const std::string& path, std::string* text_out) {
    const std::string text = read_input_file(path, "model file");
    if (text_out) *text_out = text;
    return parse_model_header(text, path);
}

namespace {

// The first medium whose layer scatters (with phase_g <= 0 when backward), or -1
int scattering_layer(const Stack& s, bool backward) {
    for (size_t i = 0; i < s.layers.size(); ++i)
        if (s.medium_scatters(i) && (!backward || !(s.layers[i].phase_g > 0.0f))) return int(i);
    return -1;
}

// Whether `when` holds on s, and the placeholders of its reason
bool condition_holds(StackCondition when, const Stack& s, std::vector<std::pair<std::string, std::string>>& fill) {
    switch (when) {
        case StackCondition::ScatteringMedium:
        case StackCondition::BackwardScatteringMedium: {
            const int i = scattering_layer(s, when == StackCondition::BackwardScatteringMedium);
            if (i < 0) return false;
            fill.push_back({"{layer}", "layer " + std::to_string(i + 1) + "'s medium scatters"});
            fill.push_back({"{phase_g}", format_shortest(s.layers[size_t(i)].phase_g)});
            return true;
        }
        case StackCondition::LambertianBase:
            for (const Layer& L : s.layers)
                if (L.kind == InterfaceKind::Lambertian) return true;
            return false;
        case StackCondition::Transmissive:
            return s.transmissive();
        case StackCondition::SubstrateNotExterior:
            fill.push_back({"{substrate_ior}", format_shortest(s.base().ior.x)});
            fill.push_back({"{exterior_ior}", format_shortest(s.exterior_ior)});
            return s.transmissive() && s.base().ior.x != s.exterior_ior;
        case StackCondition::BaseNotLambertianOrConductor:
            fill.push_back({"{base}", to_string(s.base().kind)});
            return s.base().kind != InterfaceKind::Lambertian && s.base().kind != InterfaceKind::Conductor;
        case StackCondition::BaseNotLambertian:
            fill.push_back({"{base}", to_string(s.base().kind)});
            return s.base().kind != InterfaceKind::Lambertian;
        case StackCondition::NotTwoLayers:
            fill.push_back({"{layers}", std::to_string(s.layers.size())});
            return s.layers.size() != 2;
        case StackCondition::NotCoatOverBase:   // two layers, or three: a dielectric base under the coat
            fill.push_back({"{layers}", std::to_string(s.layers.size())});
            return !(s.layers.size() == 2 ||
                     (s.layers.size() == 3 && s.layers[0].kind == InterfaceKind::Dielectric &&
                      s.layers[1].kind == InterfaceKind::Dielectric && s.layers[2].kind == InterfaceKind::Lambertian));
        case StackCondition::AbsorbingBaseMedium:
            // three layers: the medium between the base's dielectric interface and its Lambertian
            if (s.layers.size() == 3 && s.layers[1].kind == InterfaceKind::Dielectric) {
                const glm::vec3 tau = s.layers[1].optical_depth;
                fill.push_back({"{layer}", "layer 2's medium absorbs: optical depth " + format_shortest(tau.x) + ", " +
                                               format_shortest(tau.y) + ", " + format_shortest(tau.z)});
                return tau.x > 0.0f || tau.y > 0.0f || tau.z > 0.0f;
            }
            return false;
        case StackCondition::FibreDepthNot1: {
            const glm::vec3 tau = s.layers[0].optical_depth;
            fill.push_back({"{optical_depth}", format_shortest(tau.x) +
                                                   (tau.y != tau.x || tau.z != tau.x
                                                        ? ", " + format_shortest(tau.y) + ", " + format_shortest(tau.z)
                                                        : std::string())});
            return stack_has_shape(s, StackShape::FibresOverLambertian) && tau != glm::vec3(1.0f);
        }
        case StackCondition::AbsorbingMedium:
            for (size_t i = 0; i < s.layers.size(); ++i) {
                const glm::vec3 tau = s.layers[i].optical_depth;
                if (tau.x > 0.0f || tau.y > 0.0f || tau.z > 0.0f) {
                    fill.push_back({"{layer}", "layer " + std::to_string(i + 1) + "'s medium absorbs: optical depth " +
                                                   format_shortest(tau.x) + ", " + format_shortest(tau.y) + ", " +
                                                   format_shortest(tau.z)});
                    return true;
                }
            }
            return false;
        case StackCondition::CoatIorNot1_5:
        case StackCondition::CoatIorBeyond3:
        case StackCondition::CoatIorBelow1: {
            const glm::dvec3 eta = glm::dvec3(s.layers[0].ior) / double(s.exterior_ior);
            fill.push_back({"{coat_eta}",
                            format_shortest(float(eta.x)) +
                                (eta.y != eta.x || eta.z != eta.x
                                     ? " (" + format_shortest(float(eta.y)) + ", " + format_shortest(float(eta.z)) + ")"
                                     : std::string())});
            if (s.layers[0].kind != InterfaceKind::Dielectric) return true;
            bool holds = false;
            for (int c = 0; c < 3; ++c)
                holds |= when == StackCondition::CoatIorNot1_5    ? std::fabs(eta[c] - 1.5) > 1e-6
                         : when == StackCondition::CoatIorBeyond3 ? eta[c] > 3.0 + 1e-6 || eta[c] * 3.0 < 1.0 - 1e-6
                                                                  : eta[c] < 1.0;
            return holds;
        }
    }
    return false;
}

}   // namespace

std::string model_file_cannot_represent(const ModelFileHeader& h, const Stack& s, const std::string& id) {
    const std::string name = id.empty() ? h.id : id;
    // every model reads a rough interface's roughness as a GGX alpha (a user's GonioLayer has no distribution); the
    // reference's shadowing, height-correlated or separable, is a fact of the surface the models approximate alike
    for (size_t i = 0; i < s.layers.size(); ++i)
        if (s.layers[i].roughness > 0.0f && s.layers[i].distribution != MicrofacetDistribution::Ggx)
            return name + " takes GGX microfacets (its alpha is a GGX roughness); layer " + std::to_string(i + 1) +
                   "'s interface is Beckmann";
    // and every model's medium is Henyey-Greenstein's, but for a model of a fibre layer over a Lambertian (a sheen
    // model) on that shape
    const bool takes_fibres =
        std::find(h.represents.begin(), h.represents.end(), StackShape::FibresOverLambertian) != h.represents.end() &&
        stack_has_shape(s, StackShape::FibresOverLambertian);
    for (size_t i = 0; i < s.layers.size() && !takes_fibres; ++i)
        if (s.medium_scatters(i) && s.layers[i].phase != MediumPhase::Hg)
            return name + " takes Henyey-Greenstein media (a phase_g, no microflakes); layer " + std::to_string(i + 1) +
                   "'s medium is SGGX " + (s.layers[i].phase == MediumPhase::SggxFibre ? "fibres" : "flakes") +
                   ", whose extinction depends on the direction";
    for (const Refusal& r : h.refuses) {
        std::vector<std::pair<std::string, std::string>> fill{{"{id}", name}};
        if (!condition_holds(r.when, s, fill)) continue;
        std::string why = r.reason;
        for (const auto& [key, value] : fill)
            for (size_t at; (at = why.find(key)) != std::string::npos;) why.replace(at, key.size(), value);
        return why;
    }
    std::string shapes;
    for (StackShape shape : h.represents) {
        if (stack_has_shape(s, shape)) return "";
        shapes += std::string(shapes.empty() ? "" : ", ") + to_string(shape);
    }
    return name + " represents " + shapes + " (its header, " + h.path + "); this stack is none of them";
}

}   // namespace gonio
