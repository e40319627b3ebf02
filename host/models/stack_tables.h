// coat_albedo.h: the directional albedo E_coat(mu) of a two-layer stack's coat, the table the albedo-scaling
// model reads (model_coat_albedo: models.comp, and the CPU twin in model_cpu.cpp).
#pragma once
#include "kernel_interface.glsl"
#include "stack.h"
#include "stack_gpu.h"

#include <vector>

namespace gonio {

// The directional albedo E(mu) of the stack's top interface (its reflection alone), at the nodes
// coat_albedo_node_mu(i), i = 0 .. COAT_ALBEDO_NODES - 1 (kernel_interface.glsl).
std::vector<float> coat_albedo_table(const Stack& s);
std::vector<float> coat_albedo_table(const StackGpu& sg);   // the same from the stack as the models read it

}   // namespace gonio
