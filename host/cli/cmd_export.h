// cmd_export.h: `gonio export DIR --format merl|rgl-bsdf --out FILE [--source ID]`: a run over incident angles as a
// file renderers read (tools/export.py, python/gonio).
#pragma once
#include "options.h"

namespace gonio {

Command export_command();

}   // namespace gonio
