// model_file.cpp: the header of a model file (model_file.h).
#include "model_file.h"

#include <cctype>
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
    {StackShape::DielectricsOverLambertian, "dielectric-stack-over-lambertian"},
    {StackShape::DielectricsOverConductor, "dielectric-stack-over-conductor"},
    {StackShape::Slab, "slab"},
    {StackShape::Transmissive, "transmissive"},
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
        case StackShape::DielectricsOverLambertian:
            return dielectrics_over(s, InterfaceKind::Lambertian);
        case StackShape::DielectricsOverConductor:
            return dielectrics_over(s, InterfaceKind::Conductor);
        case StackShape::Transmissive:
            return s.transmissive() && dielectrics_over(s, InterfaceKind::Dielectric);
        case StackShape::Slab:
            return s.transmissive() && dielectrics_over(s, InterfaceKind::Dielectric) &&
                   s.base().ior == glm::vec3(s.exterior_ior);
    }
    return false;   // a shape without a rule here matches no stack
}

std::string builtin_model_entry(const std::string& id) {
    std::string name = "model_";
    for (char c : id) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return name;
}

ModelFileHeader parse_model_header(const std::string& text, const std::string& path, ModelFileKind kind) {
    const bool builtin = kind == ModelFileKind::BuiltIn;
    ModelFileHeader h;
    h.path = path;
    std::istringstream in(text);
    std::string raw, last_key;
    int line = 0, id_line = 0;
    bool seen_represents = false, seen_reciprocal = false, seen_energy = false, seen_summary = false,
         seen_stacks = false;
    static const std::regex key_line(R"(^([a-z][a-z-]*):\s*(.*)$)");
    // The header's lines "key: value", each with the comment lines that continue it: a user's file continues its
    // citation only (a comment line after another key is the file's own), a built-in's every key up to an empty
    // comment line
    struct Entry {
        std::string key, value;
        int line;
    };
    std::vector<Entry> entries;
    bool continues = false;
    while (std::getline(in, raw)) {
        ++line;
        const std::string t = trim(raw);
        if (t.empty() && !id_line) continue;   // blank lines before the header
        if (t.rfind("//", 0) != 0) break;   // the header ends at the first line that is not a comment
        const std::string body = trim(t.substr(2));
        if (builtin && body.empty() && id_line) break;   // a built-in's header ends at an empty comment line
        std::smatch m;
        if (!std::regex_match(body, m, key_line)) {
            if (!id_line)
                throw StackError(path, line, "expected the model's header to start with '// gonio-model: ID'");
            if (continues && !body.empty()) entries.back().value += " " + body;
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
    // a variant's suffix: "+name" ("+g2", "+g2+tir")
    static const std::regex suffix_form(R"(^(\+[a-z0-9][a-z0-9._-]*)+$)");
    auto variant_of = [&](const std::string& suffix, const Entry& e) -> ModelVariant& {
        for (ModelVariant& v : h.variants)
            if (v.suffix == suffix) return v;
        throw StackError(path, e.line, e.key + ": no 'variant: " + suffix + " = ...' line before it");
    };
    for (const Entry& e : entries) {
        const std::string &key = e.key, &value = e.value;
        const int at = e.line;
        if (key == "gonio-model") {
            static const std::regex id_form(R"(^[a-z0-9][a-z0-9._+-]{0,63}$)");
            if (!std::regex_match(value, id_form))
                throw StackError(path, at,
                                 "gonio-model: expected an id of lower-case letters, digits and . _ + - (at most "
                                 "64), got '" +
                                     value + "'");
            h.id = value;
        } else if (key == "citation") {
            h.citation = value;
        } else if (key == "represents") {
            seen_represents = true;
            std::istringstream list(value);
            std::string item;
            while (std::getline(list, item, ',')) {
                item = trim(item);
                bool found = false;
                for (const auto& k : kShapes)
                    if (item == k.name) h.represents.push_back(k.shape), found = true;
                if (!found)
                    throw StackError(path, at,
                                     "represents: unknown stack shape '" + item +
                                         "' (expected a comma-separated "
                                         "list of: " +
                                         shape_list() + ")");
            }
            if (h.represents.empty())
                throw StackError(path, at, "represents: expected at least one of: " + shape_list());
        } else if (key == "reciprocal") {
            seen_reciprocal = true;
            h.reciprocal = parse_yes_no(value, key, path, at, nullptr);
        } else if (key == "energy-conserving") {
            seen_energy = true;
            h.energy_conserving = parse_yes_no(value, key, path, at, &h.energy_note);
        } else if (builtin && key == "summary") {
            seen_summary = true;
            h.summary = value;
        } else if (builtin && key == "stacks") {
            seen_stacks = true;
            h.stacks = value;
        } else if (builtin && key == "variant") {
            // +SUFFIX = convention NAME[, NAME]: what it does differently
            static const std::regex form(R"(^(\S+)\s*=\s*convention\s+([a-z0-9, -]+?)\s*:\s*(.+)$)");
            std::smatch m;
            if (!std::regex_match(value, m, form) || !std::regex_match(m[1].str(), suffix_form))
                throw StackError(path, at,
                                 "variant: expected '+SUFFIX = convention NAME[, NAME]: what it does differently' "
                                 "(conventions g2, tir-below-media), got '" +
                                     value + "'");
            ModelVariant v;
            v.suffix = m[1];
            v.what = m[3];
            std::istringstream list(m[2].str());
            std::string name;
            while (std::getline(list, name, ',')) {
                name = trim(name);
                if (name == "g2")
                    v.convention |= MODEL_CONVENTION_G2;
                else if (name == "tir-below-media")
                    v.convention |= MODEL_CONVENTION_TIR_BELOW_MEDIA;
                else
                    throw StackError(path, at,
                                     "variant: unknown convention '" + name + "' (expected g2, tir-below-media)");
            }
            for (const ModelVariant& w : h.variants)
                if (w.suffix == v.suffix) throw StackError(path, at, "variant: " + v.suffix + " given twice");
            h.variants.push_back(v);
        } else if (builtin && key == "variant-energy-note") {
            static const std::regex form(R"(^(\S+)\s*=\s*(.+)$)");
            std::smatch m;
            if (!std::regex_match(value, m, form))
                throw StackError(path, at, "variant-energy-note: expected '+SUFFIX = the note', got '" + value + "'");
            ModelVariant& v = variant_of(m[1], e);
            v.energy_note = m[2];
            v.has_energy_note = true;
        } else {
            throw StackError(path, at,
                             "unknown header key '" + key +
                                 (builtin ? ":' (expected gonio-model, citation, summary, stacks, represents, "
                                            "reciprocal, energy-conserving, variant, variant-energy-note)"
                                          : ":' (expected gonio-model, citation, represents, "
                                            "reciprocal, energy-conserving)"));
        }
    }
    if (!id_line) throw StackError(path, 1, "expected the model's header to start with '// gonio-model: ID'");
    auto missing = [&](const char* key, const char* what) {
        throw StackError(path, id_line, std::string("the header has no '") + key + ":' line (" + what + ")");
    };
    if (!seen_represents) missing("represents", "which stacks the model represents");
    if (!seen_reciprocal) missing("reciprocal", "yes or no");
    if (!seen_energy) missing("energy-conserving", "yes or no");
    if (builtin && !seen_summary) missing("summary", "what the model does, in one line");
    if (builtin && !seen_stacks) missing("stacks", "which stacks it represents, in words");
    if (builtin) {
        const std::string entry = builtin_model_entry(h.id);
        const std::regex entry_form(
            "\\bvec3\\s+" + entry +
            R"(\s*\(\s*CoatParams\s+\w+\s*,\s*uint\s+\w+\s*,\s*vec3\s+\w+\s*,\s*vec3\s+\w+\s*\))");
        if (!std::regex_search(text, entry_form))
            throw StackError(path, id_line,
                             "the file defines no 'vec3 " + entry +
                                 "(CoatParams p, uint terms, vec3 l, vec3 v)' (a built-in model's entry: its terms' "
                                 "f in 1/sr, cosine excluded, directions away from the surface)");
        return h;
    }
    static const std::regex model_f(R"(\bvec3\s+model_f\s*\(\s*vec3\s+\w+\s*,\s*vec3\s+\w+\s*\))");
    if (!std::regex_search(text, model_f))
        throw StackError(path, id_line,
                         "the file defines no 'vec3 model_f(vec3 l, vec3 v)' (the model's f in 1/sr, "
                         "cosine excluded, directions away from the surface)");
    // a definition at the start of a line (not a mention in a comment): models/user_model.glsl, "lobe hints"
    static const std::regex lobes(R"((^|\n)[ \t]*uint[ \t]+model_lobes[ \t]*\()");
    h.has_lobe_hints = std::regex_search(text, lobes);
    return h;
}

ModelFileHeader read_model_file(const std::string& path, std::string* text_out) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw StackError(path, 0, "cannot open the model file");
    std::ostringstream s;
    s << f.rdbuf();
    if (text_out) *text_out = s.str();
    return parse_model_header(s.str(), path);
}

std::string model_file_cannot_represent(const ModelFileHeader& h, const Stack& s) {
    std::string shapes;
    for (StackShape shape : h.represents) {
        if (stack_has_shape(s, shape)) return "";
        shapes += std::string(shapes.empty() ? "" : ", ") + to_string(shape);
    }
    return h.id + " represents " + shapes + " (its header, " + h.path + "); this stack is none of them";
}

}   // namespace gonio
