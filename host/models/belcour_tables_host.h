// belcour_tables_host.h: the host side of Belcour 2018's FGD and TIR tables (shaders/lib/models/belcour_tables.glsl):
// computed on the device (shaders/tables.comp) behind an in-memory and an on-disk cache, or on the CPU twin; their
// geometry and entries.
#pragma once
#include "stack.h"
#include "stack_gpu.h"

#include <glm/glm.hpp>
#include <cstdint>
#include <memory>
#include <vector>

namespace gonio {

class VkContext;

// Belcour's tables on the CPU twin (the same code as shaders/tables.comp), layout of belcour_tables.glsl.
std::vector<float> belcour_tables_cpu(const StackGpu& sg);

// The CPU twin's tables of the (packed) stack sg for the last stack seen, per thread; each set computed when a model
// of conventions `convention` (CONVENTION_* bits) first reads it.
const std::vector<float>& belcour_tables_cpu_cached(const StackGpu& sg, uint32_t convention);

// Table geometry (shaders/lib/models/belcour_tables.glsl): entry (layer, alpha node a, mu node c) of the set with
// separable Smith G (g2 = false, the default models') or with height-correlated G2 (g2 = true, the +g2 variants).
struct BelcourTableGeometry {
    uint32_t n_mu, n_alpha;
};
BelcourTableGeometry belcour_table_geometry();
double belcour_table_mu(uint32_t c);
double belcour_table_alpha(uint32_t a);
glm::dvec3 belcour_table_fgd(const std::vector<float>& tables, uint32_t layer, uint32_t a, uint32_t c, bool g2 = false);
double belcour_table_tir(const std::vector<float>& tables, uint32_t layer, uint32_t a, uint32_t c, bool g2 = false);

// The device's tables (tables.comp), per set of interfaces: kept in memory, and on disk (belcour_tables_host.cpp:
// $GONIO_CACHE_DIR, ..., GONIO_NO_CACHE=1 turns it off).
class BelcourTableKernel {
public:
    explicit BelcourTableKernel(VkContext& ctx);
    ~BelcourTableKernel();
    BelcourTableKernel(const BelcourTableKernel&) = delete;
    BelcourTableKernel& operator=(const BelcourTableKernel&) = delete;
    // The tables for the stack's interfaces (both sets), computed on the device unless cached.
    const std::vector<float>& tables(const StackGpu& sg);
    double seconds() const;   // device seconds spent computing tables so far
private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}   // namespace gonio
