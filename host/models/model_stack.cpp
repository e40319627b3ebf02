// model_stack.cpp: see model_stack.h.
#include "model_stack.h"
#include "stack_tables.h"
#include "model_applicability.h"
#include "model_plan.h"   // mu_jump_of
#include "model_twin.h"   // TABLE_FLOATS
#include "user_model.h"

#include <cstring>
#include <stdexcept>

namespace gonio {

namespace {

void fill_slot(std::vector<float>& t, uint32_t slot, const ModelFileHeader& h, const ModelOptions& options) {
    const auto it = options.parameters.find(h.id);
    if (it != options.parameters.end() && it->second.size() != h.parameters.size())
        throw std::invalid_argument("model " + h.id + " has " + std::to_string(h.parameters.size()) +
                                    " parameters, given " + std::to_string(it->second.size()) + " values");
    for (size_t i = 0; i < h.parameters.size(); ++i)
        t.at(STACK_TABLE_PARAMETERS + slot * MODEL_MAX_PARAMETERS + i) =
            float(it != options.parameters.end() ? it->second[i] : h.parameters[i].value);
}

}   // namespace

void fill_model_parameters(std::vector<float>& t, const ModelOptions& options) {
    static_assert(MODEL_USER_PARAMETER_SLOT0 < MODEL_PARAMETER_SLOTS);
    for (size_t m = 0; m < model_registry().size(); ++m) {
        if (shader_model_of(m) >= MODEL_USER_PARAMETER_SLOT0)
            throw std::logic_error("more built-in models than parameter slots (kernel_interface.glsl)");
        fill_slot(t, shader_model_of(m), model_registry()[m].header, options);
    }
    if (options.user_models.size() > MODEL_PARAMETER_SLOTS - MODEL_USER_PARAMETER_SLOT0)
        throw std::invalid_argument("at most " + std::to_string(MODEL_PARAMETER_SLOTS - MODEL_USER_PARAMETER_SLOT0) +
                                    " model files at once");
    for (size_t k = 0; k < options.user_models.size(); ++k)
        fill_slot(t, MODEL_USER_PARAMETER_SLOT0 + uint32_t(k), options.user_models[k]->header, options);
}

void fill_model_parameters_of(std::vector<float>& t, size_t index, const ModelOptions& options) {
    fill_slot(t, shader_model_of(index), model_registry().at(index).header, options);
}

ModelStack model_stack(const Stack& s, const ModelOptions& options, BelcourTableKernel& tables) {
    ModelStack m;
    m.stack = s;
    m.gpu = pack_stack(s);
    m.mu_jump = mu_jump_of(m.gpu);
    bool need_tables = false;
    uint32_t sets = 0;   // the per-stack tables the models that run read
    for (size_t i = 0; i < model_registry().size(); ++i) {
        std::string why = model_not_selected(i, options);
        m.skipped.push_back(why.empty() ? model_cannot_represent(i, s) : why);
        need_tables |= uses_tables(i) && options.belcour_tables && m.skipped.back().empty();
        if (m.skipped.back().empty()) sets |= model_registry()[i].header.tables;
    }
    m.stack_tables = stack_tables(m.gpu, sets);
    fill_model_parameters(m.stack_tables, options);
    m.tables.assign(TABLE_FLOATS, 0.0f);
    if (need_tables) {
        const double before = tables.seconds();
        m.tables = tables.tables(m.gpu);
        m.tables.resize(TABLE_FLOATS);
        m.has_tables = true;
        m.table_seconds = tables.seconds() - before;
    }
    return m;
}

ModelStackBuffers::ModelStackBuffers(VkContext& ctx)
    : stack(ctx.make_buffer(sizeof(StackGpu), vk::BufferUsageFlagBits::eUniformBuffer, true)),
      stack_tables(ctx.make_buffer(STACK_TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, true)),
      tables(ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, true)) {}

void ModelStackBuffers::upload(const ModelStack& m) {
    std::memcpy(stack.mapped, &m.gpu, sizeof(m.gpu));
    std::memcpy(stack_tables.mapped, m.stack_tables.data(), STACK_TABLE_FLOATS * 4);
    std::memcpy(tables.mapped, m.tables.data(), TABLE_FLOATS * 4);
}

}   // namespace gonio
