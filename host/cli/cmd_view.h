// cmd_view.h: `gonio view ...`: runs gonio-view, the interactive viewer, with the same arguments.
#pragma once

namespace gonio {

int cmd_view(int argc, char** argv);

}   // namespace gonio
