// models/stack_tables.glsl: how the models read their per-stack tables (kernel_interface.glsl STACK_TABLE_*,
// computed by host/models/stack_tables.cpp): the includer provides float model_stack_table(uint i), element i of
// the buffer (models.comp and render.comp from their StackTables binding, the CPU twin from host/models/model_cpu.cpp).
#ifndef GONIO_MODELS_STACK_TABLES_GLSL
#define GONIO_MODELS_STACK_TABLES_GLSL

// A set of `nodes` values at mu = i / (nodes - 1) from `offset`, at mu by linear interpolation between its nodes
// (mu clamped to [0, 1])
GONIO_INLINE float model_stack_table_at(uint offset, uint nodes, float mu) {
    const float x = clamp(mu, 0.0f, 1.0f) * float(nodes - 1u);
    const uint i = min(uint(x), nodes - 2u);
    const float a = model_stack_table(offset + i), b = model_stack_table(offset + i + 1u);
    return a + (b - a) * (x - float(i));
}

// The model's own parameter i (its file's i-th `parameter:` line; a file reads it as param_NAME): the includer
// provides uint model_parameter_slot(), the model's slot (kernel_interface.glsl STACK_TABLE_PARAMETERS)
GONIO_INLINE float model_parameter(uint i) {
    return model_stack_table(STACK_TABLE_PARAMETERS + model_parameter_slot() * MODEL_MAX_PARAMETERS + i);
}

// E_coat at cos theta = mu (`tables: coat-albedo`: albedo-scaling, openpbr, standard-surface)
GONIO_INLINE float model_coat_albedo(float mu) {
    return model_stack_table_at(STACK_TABLE_COAT_ALBEDO, COAT_ALBEDO_NODES, mu);
}
#endif
