// gonio: a virtual gonio-photometer for layered materials. The command line: a command of the table (commands.cpp, each in its
// cmd_NAME.cpp, with its options), the help, and the exit status of what a command throws.
#include "commands.h"
#include "help.h"
#include "options.h"
#include "refusal.h"
#include "stack.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using namespace gonio;

namespace {

// gonio NAME ARGS...: its own --help, or its options parsed by its table and its run.
int run_command(const Command& c, const std::vector<std::string>& args) {
    Invocation inv = c.start();
    if (c.passes_arguments_on) return inv.run(args);
    for (const std::string& a : args)
        if (a == "--help" || a == "-h") {
            std::fputs(command_help(c).c_str(), stdout);
            return 0;
        }
    set_usage_command(c.name);
    return inv.run(parse_options(c, inv.options, args, commands()));
}

}   // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fputs(short_help(commands()).c_str(), stdout);
        return 2;
    }
    const std::string cmd = argv[1];
    try {
        if (cmd == "help" || cmd == "--help" || cmd == "-h") {
            std::fputs(full_help(commands()).c_str(), stdout);
            return 0;
        }
        if (cmd == "--version") {
            std::printf("gonio %s\n", GONIO_VERSION);
            return 0;
        }
        for (const Command& c : commands())
            if (c.name == cmd) return run_command(c, std::vector<std::string>(argv + 2, argv + argc));
        usage_error("unknown command '" + cmd + "'");
    } catch (const UsageError& e) {   // a refused command line: exit 2
        print_usage_error(e.what());
        return 2;
    } catch (const RequestRefused& e) {   // the pipeline refused what the options asked: as a refused option, exit 2
        print_usage_error(e.what());
        return 2;
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
