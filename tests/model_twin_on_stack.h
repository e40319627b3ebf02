// model_twin_on_stack.h: the CPU twin of the models (host/models/model_cpu.h, stack_tables.h, belcour_tables_host.h)
// on a Stack as a test writes it. The host's functions take the stack as the models read it, derived once by their
// caller (pack_stack); a test's stack is packed here, at each call.
#pragma once
#include "belcour_tables_host.h"
#include "model_cpu.h"
#include "model_twin.h"   // the table sets' layout (STACK_TABLE_*) and the albedo sets' nodes
#include "stack_gpu.h"
#include "stack_tables.h"

#include <string>
#include <vector>

namespace gonio_test {

inline glm::dvec3 model_value_cpu(size_t index, const gonio::Stack& s, glm::vec3 l, glm::vec3 v,
                                  const gonio::ModelOptions& options = {}) {
    return gonio::model_value_cpu(index, gonio::pack_stack(s), l, v, options);
}

inline gonio::BelcourLobesHost model_lobes_cpu(const std::string& id, const gonio::Stack& s, double mu, bool tables,
                                               uint32_t convention = 0) {
    return gonio::model_lobes_cpu(id, gonio::pack_stack(s), mu, tables, convention);
}

inline gonio::BelcourLobesHost model_lobes_cpu(const std::string& id, const gonio::Stack& s, double mu,
                                               const std::vector<float>& tables, uint32_t convention = 0) {
    return gonio::model_lobes_cpu(id, gonio::pack_stack(s), mu, tables, convention);
}

// The coat-albedo set alone: E(mu) of the stack's top interface (its reflection alone) at coat_albedo_node_mu(i)
inline std::vector<float> coat_albedo_table(const gonio::Stack& s) {
    const std::vector<float> t = gonio::stack_tables(gonio::pack_stack(s), STACK_TABLES_COAT_ALBEDO);
    return {t.begin() + STACK_TABLE_COAT_ALBEDO, t.begin() + STACK_TABLE_COAT_ALBEDO + COAT_ALBEDO_NODES};
}

inline std::vector<float> belcour_tables_cpu(const gonio::Stack& s) {
    return gonio::belcour_tables_cpu(gonio::pack_stack(s));
}

}   // namespace gonio_test
