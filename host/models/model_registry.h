// model_registry.h: the analytic layered models gonio compares with the reference: one entry per model and
// variant (id, citation, what it represents and claims, which shader code and conventions it runs with), and the
// switches they run with. The registry is read from the built-in models' files (shaders/lib/models/builtin/NN-ID.glsl,
// embedded in the binary: host/gpu/shader_sources.h), each file's header (model_file.h, ModelFileKind::BuiltIn):
// a new built-in model is one file there and nothing else (docs/MODELS.md "Adding a model").
#pragma once
#include "model_file.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gonio {

struct UserModel;   // user_model.h

struct ModelInfo {
    std::string id;
    std::string citation;
    std::string summary;   // what it does, in one line
    std::string represents;   // which stacks it can represent
    bool reciprocal;   // f(l, v) = f(v, l) by construction (tested both ways)
    bool energy_conserving;   // directional albedo <= 1 for every stack it represents, by construction (tested
        // on hard stacks); false: the model's construction does not guarantee it
    std::string energy_note;   // why not, when not
    uint32_t shader_model = 0;   // the model's code: its file's place among shaders/lib/models/builtin/*.glsl (by
        // name), the index of its SPIR-V modules and of eval_model in models/all.glsl; a variant shares its base's
    uint32_t convention = 0;   // CONVENTION_* bits (belcour_tables.glsl): 0 is what the model's official code
        // computes; a variant (id base+g2, +tir) sets gonio's alternatives (MODEL_CONVENTION_*, model_file.h)
    std::string file;   // the model's file ("shaders/lib/models/builtin/00-ww09.glsl"), a variant's its base's
    ModelFileHeader header;   // its header, as parsed (represents: the stack shapes, for model_file_cannot_represent)
};

// A built-in model's file: its path (messages) and text.
struct BuiltinModelFile {
    std::string path, text;
};
// The built-in models' files embedded in the binary (shaders/lib/models/builtin/*.glsl, in name order).
std::vector<BuiltinModelFile> builtin_model_files();
// The registry made from these files: the base models in the files' order (code = place), then each one's variants
// (its `variant:` lines, in order). Throws StackError (FILE:LINE) for a bad header or a duplicate id.
std::vector<ModelInfo> make_model_registry(const std::vector<BuiltinModelFile>& files);

const std::vector<ModelInfo>& model_registry();   // make_model_registry(builtin_model_files()), once
// The registry entry of that id (a model or a variant), or nullptr.
const ModelInfo* find_model(const std::string& id);

// The code of registry entry `index` (ModelInfo::shader_model): a variant runs its base model's code.
uint32_t shader_model_of(size_t index);
// The id of the base model of code `code` (its file's `gonio-model:`).
const std::string& code_id(uint32_t code);
// Models that read the FGD/TIR tables and whose lobes the device computes once per dispatch (their file's `plan:
// lobes` or `lobes-symmetric`: Belcour's, tm21).
bool uses_tables(size_t index);

// Switches of the models.
struct ModelOptions {
    bool belcour_tables = true;   // Belcour's models: FGD and TIR tables (false: Fresnel at the mean cosine, no
        // TIR term)
    std::vector<std::string> selected;   // the ids of the models to run (`--models`); empty: every model
    // with `selected` empty: also the registry's variants (ModelInfo::convention != 0); false: the models as their
    // authors publish them, and the --model files (the commands' default; `--models all` sets it)
    bool variants = true;
    std::vector<std::shared_ptr<const UserModel>> user_models;   // `--model FILE`: run after the built-in ones
    // the models' own parameters (their files' `parameter:` lines) by model id, in the header's order (a variant
    // shares its model's: give them under the base id); a model not here has its defaults (model_stack.h)
    std::map<std::string, std::vector<double>> parameters;
    // built-in ids integrated as a black box though model_plan.cpp has a plan for them, as a built-in model file
    // with no plan is (tests: the black box of a built-in against its plan)
    std::vector<std::string> as_black_box;
};

// "" where model `index` runs under these options, else why not ("not selected (--models ...)").
std::string model_not_selected(size_t index, const ModelOptions& o);
// The same for a model by id (a user's model).
std::string model_id_not_selected(const std::string& id, const ModelOptions& o);

}   // namespace gonio
