// cmd_simulate.h: `gonio simulate`: the reference on a stack: EXR, slices.csv, summary.json, state.gonio.
#pragma once
#include "options.h"

namespace gonio {

Command simulate_command();

}   // namespace gonio
