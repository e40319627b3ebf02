// cmd_render.h: `gonio render STACK`: the reference and every model that can represent the stack on a sphere
// under an environment map, their differences and HDR-FLIP (docs/RENDER.md; the pipeline: render_case.h).
#pragma once
#include "options.h"

namespace gonio {

Command render_command();

}   // namespace gonio
