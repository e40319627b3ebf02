// cmd_compare.h: `gonio compare`: simulate, then every model that can represent the stack on the same bins, how far
// each is from the reference; figures and report.html; with --render, the sphere renderings too.
#pragma once
#include "options.h"

namespace gonio {

Command compare_command();

}   // namespace gonio
