// cmd_view.h: `gonio view ...`: runs gonio-view, the interactive viewer, with the same arguments.
#pragma once
#include "options.h"

namespace gonio {

Command view_command();

}   // namespace gonio
