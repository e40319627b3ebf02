// cmd_export.h: `gonio export DIR --format merl|rgl-bsdf --out FILE [--source ID]`: a run over incident angles as a
// file renderers read (tools/export.py, python/gonio).
#pragma once

namespace gonio {

int cmd_export(int argc, char** argv);

}   // namespace gonio
