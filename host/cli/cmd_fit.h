// cmd_fit.h: `gonio fit`: the values of a model's stack keys that bring it closest to the reference.
#pragma once
#include "options.h"

namespace gonio {

Command fit_command();

}   // namespace gonio
