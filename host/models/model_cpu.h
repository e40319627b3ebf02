// model_cpu.h: the analytic models on the CPU, compiled from the very same shader sources (shaders/lib/models/*.glsl)
// through GLM: f(l, v) of a model, Belcour's and tm21's lobes. For the tests, gonio bench and the plan. Each takes the
// stack as the models read it (pack_stack; ModelStack::gpu), derived once by its caller.
#pragma once
#include "model_registry.h"
#include "stack.h"
#include "stack_gpu.h"

#include <glm/glm.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gonio {

// Belcour's lobes at incident cosine mu, through the CPU twin: energies, roughnesses, transmitted lobe.
struct BelcourLobesHost {
    std::vector<glm::dvec3> e;
    std::vector<double> alpha;
    glm::dvec3 e_t{0.0};
    double alpha_t = 0.0;
};
// The lobes of the built-in model of code `code` at incident cosine mu, from its file's own GONIO_MODEL_LOBES hook
// (a `plan: lobes` model), with these tables (nullptr: none) and CONVENTION_* bits.
BelcourLobesHost model_lobes_cpu(uint32_t code, const StackGpu& sg, double mu, const float* tables,
                                 uint32_t convention);
// The roughness the two-layer model of code `code` evaluates its base lobe at on this stack: its file's
// GONIO_MODEL_BASE_ALPHA (a coat's roughening of the base: openpbr), else the base's own (at least MODEL_MIN_ALPHA);
// convention: the entry's CONVENTION_* bits.
double model_base_alpha_cpu(uint32_t code, const StackGpu& sg, uint32_t convention);
// The lobes (energies and roughnesses) of the built-in model `id` (a file with GONIO_MODEL_LOBES: Belcour's, tm21,
// whose lobe 0 is drawn as the exact top BRDF) at mu, through the CPU twin: with the twin's FGD / TIR tables (tables
// true) or none, or with the given ones (e.g. ModelEvaluator::belcour_tables, the device's). convention: CONVENTION_*
// bits (0: the official code's conventions). Throws std::invalid_argument for an unknown id.
BelcourLobesHost model_lobes_cpu(const std::string& id, const StackGpu& sg, double mu, bool tables,
                                 uint32_t convention = 0);
BelcourLobesHost model_lobes_cpu(const std::string& id, const StackGpu& sg, double mu, const std::vector<float>& tables,
                                 uint32_t convention = 0);
// Belcour's roughness <-> linearised variance mapping (the GLSL functions, through the CPU twin).
double belcour_variance_of(double alpha);
double belcour_roughness_of(double sigma);

// f(l, v) of one model at one pair of directions (z = normal), through the CPU twin of the shader code.
// v.z < 0: the transmission side (models with a transmitted lobe).
glm::dvec3 model_value_cpu(size_t index, const StackGpu& sg, glm::vec3 l, glm::vec3 v,
                           const ModelOptions& options = {});

// The terms of a model (models/common.glsl TERM_TOP, TERM_BASE, TERM_DIFFUSE): its top-interface reflection (lobe 0),
// everything that went through the top interface (the lobes below, the transmitted lobe; a dielectric base's
// interface lobe), and a dielectric base's diffuse under its interface.
constexpr uint32_t kModelTermTop = 1u, kModelTermBase = 2u, kModelTermDiffuse = 4u;
constexpr uint32_t kModelTermAll = kModelTermTop | kModelTermBase | kModelTermDiffuse;

// The same CPU twin for many evaluations of one model on one stack: its per-stack tables and Belcour's tables
// computed once. value(l, v) computes exactly what model_value_cpu(index, sg, l, v, options) does; `terms` selects
// terms.
// `tables`: Belcour's tables to use instead of the CPU twin's (e.g. ModelEvaluator::belcour_tables, the device's,
// which agree with the twin's to 7.5e-4). Safe to use from several threads at once (each call sets the twin's
// per-thread environment).
class ModelCpu {
public:
    ModelCpu(size_t index, const StackGpu& sg, const ModelOptions& options = {},
             const std::vector<float>* tables = nullptr);
    glm::dvec3 value(glm::vec3 l, glm::vec3 v, uint32_t terms = kModelTermAll) const;

private:
    size_t index_;
    std::vector<float> stack_tables_, tables_;
    std::vector<unsigned char> stack_;   // the packed StackGpu (stack_gpu.h), kept opaque here
    bool use_tables_;
};

}   // namespace gonio
