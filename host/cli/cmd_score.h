// cmd_score.h: `gonio score`: a model's values at the nodes of gonio nodes, scored on a reference run's bins.
#pragma once
#include "options.h"

namespace gonio {

Command score_command();

}   // namespace gonio
