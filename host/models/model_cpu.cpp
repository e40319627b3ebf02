#include "model_cpu.h"
#include "belcour_tables_host.h"
#include "stack_tables.h"
#include "model_stack.h"   // fill_model_parameters
#include "model_twin.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

// What the models read from their environment (model_twin.h; shaders/models.comp provides the same from its
// buffers): the per-stack tables (stack_tables.h: the coat's directional albedo E_coat(mu), the production models'
// energy tables), Belcour's the whole stack and the FGD / TIR tables. Here through these per-thread pointers, set
// around each evaluation.
static thread_local const float* g_stack_tables = nullptr;
static thread_local const gonio::StackGpu* g_stack = nullptr;
static thread_local const float* g_tables = nullptr;
static thread_local bool g_use_tables = true;
static thread_local uint32_t g_convention = 0;
static thread_local uint32_t g_parameter_slot = 0;
float model_stack_table(uint i) { return g_stack_tables[i]; }
uint model_layer_count() { return stack_layer_count(g_stack->info); }
LayerGpu model_layer(uint i) { return g_stack->layers[i]; }
bool model_use_tables() { return g_use_tables; }
float model_table(uint i) { return g_tables ? g_tables[i] : 0.0f; }
uint model_convention() { return g_convention; }
uint model_parameter_slot() { return g_parameter_slot; }

static_assert(gonio::kModelTermTop == TERM_TOP && gonio::kModelTermBase == TERM_BASE &&
                  gonio::kModelTermDiffuse == TERM_DIFFUSE && gonio::kModelTermAll == TERM_ALL,
              "the models' terms, host and shaders");

namespace gonio {

BelcourLobesHost model_lobes_cpu(uint32_t code, const StackGpu& sg, double mu, const float* tables,
                                 uint32_t convention) {
    g_stack = &sg;
    g_use_tables = tables != nullptr;
    g_convention = convention;
    g_tables = tables;
    BelcourLobes b;
    const bool has = eval_model_lobes(code, float(mu), tables != nullptr, b);
    g_stack = nullptr;
    if (!has) throw std::logic_error("model_lobes_cpu: model " + code_id(code) + " has no lobes (GONIO_MODEL_LOBES)");
    BelcourLobesHost h;
    for (uint32_t k = 0; k < b.count; ++k) {
        h.e.push_back(glm::dvec3(b.e[k]));
        h.alpha.push_back(b.alpha[k]);
    }
    h.e_t = glm::dvec3(b.e_t);
    h.alpha_t = b.alpha_t;
    return h;
}

bool eval_model_artist_parameters_on(uint32_t code, const StackGpu& sg, CoatParams p, vec3 diffuse, ArtistValues& a) {
    g_stack = &sg;
    const bool has = eval_model_artist_parameters(code, p, diffuse, a);
    g_stack = nullptr;
    return has;
}

double model_base_alpha_cpu(uint32_t code, const StackGpu& sg, uint32_t convention) {
    g_convention = convention;
    const double a = eval_model_base_alpha(code, coat_params(sg.layers[0], sg.layers[1]));
    g_convention = 0;
    return a;
}

namespace {
uint32_t code_of(const std::string& id) {
    if (const ModelInfo* m = find_model(id)) return m->shader_model;
    throw std::invalid_argument("no built-in model '" + id + "'");
}
}   // namespace

BelcourLobesHost model_lobes_cpu(const std::string& id, const StackGpu& sg, double mu, bool tables,
                                 uint32_t convention) {
    return model_lobes_cpu(code_of(id), sg, mu, tables ? belcour_tables_cpu_cached(sg, convention).data() : nullptr,
                           convention);
}
BelcourLobesHost model_lobes_cpu(const std::string& id, const StackGpu& sg, double mu, const std::vector<float>& tables,
                                 uint32_t convention) {
    return model_lobes_cpu(code_of(id), sg, mu, tables.data(), convention);
}

double belcour_variance_of(double alpha) { return belcour_roughness_to_variance(float(alpha)); }
double belcour_roughness_of(double sigma) { return belcour_variance_to_roughness(float(sigma)); }

glm::dvec3 model_value_cpu(size_t index, const StackGpu& sg, glm::vec3 l, glm::vec3 v, const ModelOptions& options) {
    // the per-stack tables the model reads depend on the packed stack only: keep the last ones per thread
    static thread_local std::vector<unsigned char> last_stack;
    static thread_local uint32_t last_sets = ~0u;
    static thread_local std::vector<float> table;
    const uint32_t sets = model_registry().at(index).header.tables;
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(&sg);
    if (sets != last_sets || last_stack.size() != sizeof sg || std::memcmp(last_stack.data(), bytes, sizeof sg) != 0) {
        table = stack_tables(sg, sets);
        last_stack.assign(bytes, bytes + sizeof sg);
        last_sets = sets;
    }
    fill_model_parameters_of(table, index, options);   // not part of the cache's key: the options give them
    g_stack_tables = table.data();
    g_stack = &sg;
    g_use_tables = options.belcour_tables;
    g_convention = model_registry().at(index).convention;
    g_parameter_slot = shader_model_of(index);
    g_tables =
        uses_tables(index) && options.belcour_tables ? belcour_tables_cpu_cached(sg, g_convention).data() : nullptr;
    CoatParams p = coat_params(sg.layers[0], sg.layers[1]);
    glm::dvec3 f(eval_model(shader_model_of(index), p, TERM_ALL, l, v));
    g_stack = nullptr;
    return f;
}

ModelCpu::ModelCpu(size_t index, const StackGpu& sg, const ModelOptions& options, const std::vector<float>* tables)
    : index_(index), use_tables_(options.belcour_tables) {
    // what model_value_cpu sets up per call: its per-stack tables, Belcour's tables
    stack_tables_ = stack_tables(sg, model_registry().at(index).header.tables);
    fill_model_parameters_of(stack_tables_, index, options);
    stack_.resize(sizeof(StackGpu));
    std::memcpy(stack_.data(), &sg, sizeof sg);
    if (uses_tables(index) && options.belcour_tables)
        tables_ = tables ? *tables : belcour_tables_cpu_cached(sg, model_registry().at(index).convention);
}

glm::dvec3 ModelCpu::value(glm::vec3 l, glm::vec3 v, uint32_t terms) const {
    const StackGpu* sg = reinterpret_cast<const StackGpu*>(stack_.data());
    g_stack_tables = stack_tables_.data();
    g_stack = sg;
    g_use_tables = use_tables_;
    g_convention = model_registry().at(index_).convention;
    g_parameter_slot = shader_model_of(index_);
    g_tables = tables_.empty() ? nullptr : tables_.data();
    CoatParams p = coat_params(sg->layers[0], sg->layers[1]);
    glm::dvec3 f(eval_model(shader_model_of(index_), p, terms, l, v));
    g_stack = nullptr;
    return f;
}

}   // namespace gonio
