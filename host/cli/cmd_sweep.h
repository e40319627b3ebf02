// cmd_sweep.h: `gonio sweep SWEEP.toml`: a sweep, or a shard of one, or its timing (--bench).
#pragma once
#include "options.h"

namespace gonio {

Command sweep_command();

}   // namespace gonio
