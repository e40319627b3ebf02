// cmd_merge.h: `gonio merge DIR`: the shards of a sweep (DIR/configs/) gathered into DIR/sweep.csv.
#pragma once
#include "options.h"

namespace gonio {

Command merge_command();

}   // namespace gonio
