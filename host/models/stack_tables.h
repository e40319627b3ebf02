// stack_tables.h: the models' per-stack tables (kernel_interface.glsl STACK_TABLE_*), which the host computes for
// the stack at hand and models.comp, render.comp and the CPU twin read (model_stack_table): the table sets the
// built-in model files declare (`// table: NAME FLOATS`), each filled by its file's GONIO_MODEL_TABLES hook with the
// quadrature primitives model_twin.h declares.
#pragma once
#include "kernel_interface.glsl"
#include "stack_gpu.h"

#include <cstdint>
#include <vector>

namespace gonio {

// STACK_TABLE_FLOATS floats: the sets named in `sets` (STACK_TABLES_* bits) computed for the stack where it is two
// layers over an opaque base, or three with a dielectric base over a Lambertian (the models that read them take no
// other stack), zeros elsewhere.
std::vector<float> stack_tables(const StackGpu& sg, uint32_t sets);

}   // namespace gonio
