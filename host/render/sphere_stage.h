// sphere_stage.h: what gonio render computes (docs/RENDER.md), in the order it computes it: the environment (read
// first: a broken map is refused before anything is traced), the reference's table over incident angles (given, or
// traced now in two independent halves), the reference on the sphere from the table, and every model that can
// represent the stack on the device under the same environment.
#pragma once
#include "environment.h"
#include "model_render.h"
#include "reference.h"
#include "reference_render.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace gonio {

class VkContext;

struct SphereStageRequest {
    const Stack* stack = nullptr;   // the models' stack, and the table's when it is traced now
    std::string env;   // --env: a name or a file, read first, its clamped texels said on stderr
    const Environment* environment = nullptr;   // an environment read already (then env is not read)
    const ReferenceTable* table = nullptr;   // a table made already (--reference, --spectral), else traced now:
    SimOptions table_half;   // one half's options (angles, paths, progress); the seed is the first half's
    ModelRenderOptions models;
    bool quiet = false;   // no progress lines
};

struct SphereStage {
    Environment env;
    ReferenceTable table;
    std::optional<std::array<SimResult, 2>> halves;   // the table's halves, when traced now
    double table_seconds = 0;   // host clock: tracing the table (0 when given)
    ReferenceRender reference;
    std::vector<ModelRender> models;
    ModelRenderStage model_stage;
};

// The environment by name or file (load_environment), its clamped texels reported on stderr.
Environment load_render_environment(const std::string& name);
// The render's table traced now: two independent halves of o (its angles, o.paths each), the second's seed the
// first's plus 0x9e3779b9 (other seeds, other paths); o.seed is the first's.
std::array<SimResult, 2> simulate_table_halves(VkContext& ctx, const Stack& s, SimOptions o);
SphereStage render_sphere_stage(VkContext& ctx, const SphereStageRequest& r);

}   // namespace gonio
