// cmd_nodes.h: `gonio nodes` (where to evaluate a model, as files) and `gonio score` (its values on a reference).
#pragma once

namespace gonio {

int cmd_nodes(int argc, char** argv);
int cmd_score(int argc, char** argv);

}   // namespace gonio
