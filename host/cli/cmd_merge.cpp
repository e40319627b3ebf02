#include "cmd_merge.h"
#include "python_tool.h"
#include "sweep.h"

#include <cstdio>
#include <string>

namespace gonio {

namespace {

int run_merge(NoSettings&, const std::vector<std::string>& operands) {
    if (operands.size() != 1) usage_error("merge takes one sweep output directory");
    const std::string& dir = operands[0];
    uint64_t rows = merge_sweep(dir);
    std::printf("wrote %s/sweep.csv (%llu rows) and timings.csv\n", dir.c_str(), (unsigned long long)rows);
    run_python_tool("sweep_plot.py", dir, "the sweep figures");
    return 0;
}

}   // namespace

Command merge_command() {
    return {"merge", "DIR",
            "gather the shards of a sweep (DIR/configs/) into DIR/sweep.csv, byte-identical to an unsplit sweep's", "",
            invocation(&no_options, &run_merge)};
}

}   // namespace gonio
