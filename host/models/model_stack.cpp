// model_stack.cpp: see model_stack.h.
#include "model_stack.h"
#include "stack_tables.h"
#include "model_applicability.h"
#include "model_plan.h"   // mu_jump_of
#include "model_twin.h"   // TABLE_FLOATS

#include <cstring>

namespace gonio {

ModelStack model_stack(const Stack& s, const ModelOptions& options, BelcourTableKernel& tables) {
    ModelStack m;
    m.stack = s;
    m.gpu = pack_stack(s);
    m.gpu.info.z = s.exterior_ior;   // the walk's StackGpu leaves it 0
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
