// gonio: a virtual gonio-photometer for layered materials. The command line: which command runs (one file each,
// cmd_*.cpp), the help, and the exit status of what it throws.
#include "args.h"
#include "cmd_bench.h"
#include "cmd_check.h"
#include "cmd_devices.h"
#include "cmd_export.h"
#include "cmd_models.h"
#include "cmd_nodes.h"
#include "cmd_random_stack.h"
#include "cmd_render.h"
#include "cmd_simulate.h"
#include "cmd_sweep.h"
#include "cmd_view.h"
#include "help.h"
#include "stack.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

using namespace gonio;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fputs(short_help().c_str(), stdout);
        return 2;
    }
    std::string cmd = argv[1];
    try {
        if (cmd == "help" || cmd == "--help" || cmd == "-h") {
            std::fputs(full_help().c_str(), stdout);
            return 0;
        }
        if (cmd == "--version") {
            std::printf("gonio %s\n", GONIO_VERSION);
            return 0;
        }
        if (cmd != "view")   // gonio COMMAND --help: the command's own help (the viewer has its own)
            for (int i = 2; i < argc; ++i)
                if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
                    std::fputs(command_help(cmd).c_str(), stdout);
                    return 0;
                }
        if (cmd == "sweep") return cmd_sweep(argc, argv);
        if (cmd == "merge") return cmd_merge(argc, argv);
        if (cmd == "export") return cmd_export(argc, argv);
        if (cmd == "nodes") return cmd_nodes(argc, argv);
        if (cmd == "score") return cmd_score(argc, argv);
        if (cmd == "render") return cmd_render(argc, argv);
        if (cmd == "view") return cmd_view(argc, argv);
        Args a = parse_args(cmd, argc, argv, 2);
        if (cmd == "devices") return cmd_devices();
        if (cmd == "check") return cmd_check(a);
        if (cmd == "simulate") return cmd_simulate(a, false);
        if (cmd == "compare") return cmd_simulate(a, true);
        if (cmd == "models") return cmd_models();
        if (cmd == "bench") return cmd_bench(a);
        if (cmd == "random-stack") return cmd_random_stack(a);
        usage_error("unknown command '" + cmd + "'");
    } catch (const StackError& e) {   // a refused input file: exit 2
        std::fprintf(stderr, "gonio: %s\n", e.what());
        return 2;
    } catch (const std::invalid_argument& e) {   // a refused option or input (checked before any work): exit 2
        std::fprintf(stderr, "gonio: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {   // a failure while running: exit 1
        std::fprintf(stderr, "gonio: error: %s\n", e.what());
        return 1;
    }
}
