// model_stack.cpp: see model_stack.h.
#include "model_stack.h"
#include "coat_albedo.h"
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
    m.coat_albedo.assign(COAT_ALBEDO_NODES, 0.0f);
    if (s.layers.size() == 2 && !s.transmissive()) m.coat_albedo = coat_albedo_table(m.gpu);
    m.mu_jump = mu_jump_of(m.gpu);
    bool need_tables = false;
    for (size_t i = 0; i < model_registry().size(); ++i) {
        std::string why = model_not_selected(i, options);
        m.skipped.push_back(why.empty() ? model_cannot_represent(i, s) : why);
        need_tables |= uses_tables(i) && options.belcour_tables && m.skipped.back().empty();
    }
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
      coat_albedo(ctx.make_buffer(COAT_ALBEDO_NODES * 4, vk::BufferUsageFlagBits::eStorageBuffer, true)),
      tables(ctx.make_buffer(TABLE_FLOATS * 4, vk::BufferUsageFlagBits::eStorageBuffer, true)) {}

void ModelStackBuffers::upload(const ModelStack& m) {
    std::memcpy(stack.mapped, &m.gpu, sizeof(m.gpu));
    std::memcpy(coat_albedo.mapped, m.coat_albedo.data(), COAT_ALBEDO_NODES * 4);
    std::memcpy(tables.mapped, m.tables.data(), TABLE_FLOATS * 4);
}

}   // namespace gonio
