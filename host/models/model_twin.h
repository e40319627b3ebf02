// model_twin.h: the analytic models' shader code (shaders/lib/models/*.glsl) compiled as C++ through GLM, with
// the constants the kernels share with the host (kernel_interface.glsl). For the files of host/models only.
#pragma once
#include "stack_gpu.h"
#include "kernel_interface.glsl"

// What the models read from their environment: shaders/models.comp provides them from its buffers, the CPU twin
// (model_cpu.cpp) from per-thread pointers set around each evaluation.
float model_stack_table(uint i);   // the per-stack tables (kernel_interface.glsl STACK_TABLE_*)
uint model_layer_count();
LayerGpu model_layer(uint i);
bool model_use_tables();
float model_table(uint i);   // Belcour's FGD / TIR tables (models/belcour_tables.glsl layout)
uint model_convention();   // CONVENTION_* bits
uint model_parameter_slot();   // the model's slot of parameters (kernel_interface.glsl STACK_TABLE_PARAMETERS)

#include "models/all.glsl"
