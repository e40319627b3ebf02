// cmd_models.h: `gonio models`: the models' ids, citations, and which stacks each represents.
#pragma once
#include "options.h"

namespace gonio {

Command models_command();

}   // namespace gonio
