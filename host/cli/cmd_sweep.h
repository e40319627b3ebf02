// cmd_sweep.h: `gonio sweep SWEEP.toml` (a sweep, or a shard of one; --bench) and `gonio merge DIR` (its shards into
// sweep.csv). Both parse their own options.
#pragma once

namespace gonio {

int cmd_sweep(int argc, char** argv);
int cmd_merge(int argc, char** argv);

}   // namespace gonio
