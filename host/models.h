// models.h: the analytic layered models gonio compares with the reference, evaluated as bin averages on the
// reference's bins by shaders/models.comp.
#pragma once
#include "reference.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct ModelInfo {
    std::string id;
    std::string citation;
    std::string summary;     // what it does, in one line
    std::string represents;  // which stacks it can represent
    bool reciprocal;         // f(l, v) = f(v, l) by construction (tested both ways)
};

const std::vector<ModelInfo>& model_registry();

// "" when model `index` can represent the stack; otherwise why not.
std::string model_cannot_represent(size_t index, const Stack& s);

struct ModelSlices {
    std::string id;
    std::string not_applicable;                  // non-empty: the reason; f is then empty
    std::vector<std::vector<glm::dvec3>> f;      // per incident angle: reflection-side bin averages (1/sr)
};

struct ModelGrid {                               // the bins and angles to evaluate on (those of a reference run)
    uint32_t n_theta, n_phi;
    double dtheta_deg, dphi_deg;
    std::vector<double> theta_i_deg;
};
ModelGrid model_grid(const SimResult& r);

// What evaluating one model cost, over all incident angles.
struct ModelCost {
    double wall_seconds = 0;      // host clock, including the first dispatch's JIT compile
    double device_seconds = 0;    // device timestamps around the model's dispatches
    uint64_t evaluations = 0;     // evaluations of f(l, v) (quadrature nodes and lobe-grid nodes)
};

// Every model in the registry on the grid, with what each cost.
std::vector<ModelSlices> evaluate_models(VkContext& ctx, const Stack& s, const ModelGrid& grid,
                                         std::vector<ModelCost>* costs = nullptr);

// The directional albedo E(mu) of the stack's top interface (its reflection alone), at mu = i / 64, i = 0..64.
std::vector<float> coat_albedo_table(const Stack& s);

// f(l, v) of one model at one pair of directions (z = normal), through the CPU twin of the shader code.
glm::dvec3 model_value_cpu(size_t index, const Stack& s, glm::vec3 l, glm::vec3 v);

}  // namespace gonio
