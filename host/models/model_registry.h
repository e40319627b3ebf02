// model_registry.h: the analytic layered models gonio compares with the reference: one entry per model and
// variant (id, citation, what it represents and claims, which shader code and conventions it runs with), and the
// switches they run with.
#pragma once
#include <cstddef>
#include <cstdint>
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
    uint32_t shader_model = 0;   // the model's code in shaders/lib/models/all.glsl (MODEL_*): a variant shares its
        // base model's code
    uint32_t convention = 0;   // CONVENTION_* bits (belcour_tables.glsl): 0 is what the model's official code
        // computes; a variant (id base+g2, +tir) sets gonio's alternatives
};

// The models' conventions (ModelInfo::convention bits, CONVENTION_* in shaders/lib/models/belcour_tables.glsl).
constexpr uint32_t MODEL_CONVENTION_G2 = 1;   // height-correlated Smith G2 in lobes and FGD/TIR tables
constexpr uint32_t MODEL_CONVENTION_TIR_BELOW_MEDIA = 2;   // Belcour's TIR term kept below an absorbing medium

const std::vector<ModelInfo>& model_registry();

// The code (MODEL_*, shaders/lib/models/all.glsl) of registry entry `index`: a variant runs its base model's code.
uint32_t shader_model_of(size_t index);
// Belcour's models (forward, symmetric, top-lobe) and their variants.
bool is_belcour(size_t index);
// Models that read the FGD/TIR tables and whose lobes the device computes once per dispatch (Belcour's, tm21).
bool uses_tables(size_t index);

// Switches of the models.
struct ModelOptions {
    bool belcour_tables = true;   // Belcour's models: FGD and TIR tables (false: Fresnel at the mean cosine, no
        // TIR term)
    std::vector<std::string> selected;   // the ids of the models to run (`--models`); empty: every model
    std::vector<std::shared_ptr<const UserModel>> user_models;   // `--model FILE`: run after the built-in ones
};

// "" where model `index` runs under these options, else why not ("not selected (--models ...)").
std::string model_not_selected(size_t index, const ModelOptions& o);
// The same for a model by id (a user's model).
std::string model_id_not_selected(const std::string& id, const ModelOptions& o);

}   // namespace gonio
