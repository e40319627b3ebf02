// model_stack.h: what a stack implies for the analytic models, derived once per stack and taken by every host of the
// model kernels (the evaluator of compare, sweeps and bench; gonio render): which models run on it and why the others
// do not, the stack as the model kernels read it, the per-stack tables they read (the coat's albedo, ...), Belcour's tables where a model that runs
// reads them; and the device buffers that hold them, bound by models.comp and render.comp alike.
#pragma once
#include "belcour_tables_host.h"
#include "model_registry.h"
#include "stack_gpu.h"
#include "vk_context.h"

#include <string>
#include <vector>

namespace gonio {

struct ModelStack {
    Stack stack;   // the stack as described (the plan reads its layers' parameters in double)
    StackGpu gpu;   // pack_stack (info.z: the exterior's absolute IOR, which a user's model reads)
    // the per-stack tables (STACK_TABLE_FLOATS, stack_tables.h): the sets the models that run read (their `tables:`),
    // zeros elsewhere
    std::vector<float> stack_tables;
    std::vector<float> tables;   // Belcour's FGD and TIR tables (TABLE_FLOATS), zeros where no model reads them
    bool has_tables = false;
    double table_seconds = 0;   // the device time the tables took (0: from the cache or none)
    double mu_jump = 0;   // mu_jump_of(gpu): where Belcour's mean direction is totally reflected inside
    std::vector<std::string> skipped;   // per registry index: "" where the model runs, else why not
};

// The models of the registry that run on the stack with these options (not selected, or cannot represent it: why
// not), and what they read; tables: where Belcour's tables come from when a model that runs reads them.
ModelStack model_stack(const Stack& s, const ModelOptions& options, BelcourTableKernel& tables);

// The models' own parameters into the per-stack tables t (STACK_TABLE_PARAMETERS): each built-in model's at its
// code's slot, the k-th user model's (options.user_models) at MODEL_USER_PARAMETER_SLOT0 + k; from options.parameters
// where given, else the defaults. Throws std::invalid_argument for a wrong count of values.
void fill_model_parameters(std::vector<float>& t, const ModelOptions& options);
// The same for the built-in model of registry index `index` alone (what its CPU twin reads).
void fill_model_parameters_of(std::vector<float>& t, size_t index, const ModelOptions& options);

// The buffers of a ModelStack on the device (mapped), at the bindings MODEL_BINDING_* of models.comp and
// RENDER_BINDING_* of render.comp.
struct ModelStackBuffers {
    Buffer stack, stack_tables, tables;
    explicit ModelStackBuffers(VkContext& ctx);
    void upload(const ModelStack& m);
};

}   // namespace gonio
