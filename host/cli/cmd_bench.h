// cmd_bench.h: `gonio bench`: paths per second of the reference (device, general walk, CPU twin), and with --out
// the reference's convergence, the models' cost against their error (Pareto) and the error atlas.
#pragma once
#include "options.h"

namespace gonio {

Command bench_command();

}   // namespace gonio
