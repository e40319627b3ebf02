// cmd_nodes.h: `gonio nodes`: where to evaluate a model written in any language, as files (gonio score reads its
// values back).
#pragma once
#include "options.h"

namespace gonio {

Command nodes_command();

}   // namespace gonio
