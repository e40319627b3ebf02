// cmd_render.h: `gonio render STACK`: the reference and every model that can represent the stack on a sphere
// under an environment map, their differences and HDR-FLIP (docs/RENDER.md).
#pragma once

namespace gonio {

int cmd_render(int argc, char** argv);

}   // namespace gonio
