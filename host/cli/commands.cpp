// commands.cpp: see commands.h.
#include "commands.h"
#include "cmd_bench.h"
#include "cmd_check.h"
#include "cmd_compare.h"
#include "cmd_devices.h"
#include "cmd_export.h"
#include "cmd_fit.h"
#include "cmd_merge.h"
#include "cmd_models.h"
#include "cmd_nodes.h"
#include "cmd_random_stack.h"
#include "cmd_render.h"
#include "cmd_score.h"
#include "cmd_simulate.h"
#include "cmd_sweep.h"
#include "cmd_view.h"

#include <stdexcept>

namespace gonio {

// a new command is one row here (and its cmd_NAME.{h,cpp})
const std::vector<Command>& commands() {
    static const std::vector<Command> all = {
        devices_command(), check_command(), simulate_command(),     compare_command(), fit_command(),
        models_command(),  bench_command(), random_stack_command(), sweep_command(),   merge_command(),
        export_command(),  nodes_command(), score_command(),        render_command(),  view_command(),
    };
    return all;
}

const Command& command_named(const std::string& name) {
    for (const Command& c : commands())
        if (c.name == name) return c;
    throw std::invalid_argument("no command " + name);
}

}   // namespace gonio
