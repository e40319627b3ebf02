#include "cmd_check.h"
#include "lambertian_series.h"
#include "stack.h"

#include <cstdio>

namespace gonio {

namespace {

int run_check(NoSettings&, const std::vector<std::string>& operands) {
    if (operands.size() != 1) usage_error("check takes one stack file");
    Stack s = parse_stack_file(operands[0]);
    std::printf("%s", describe_stack(s).c_str());
    // which walk simulate runs on it (docs/PHYSICS.md, "The Lambertian series")
    const LambertianSeries ls = lambertian_series(s);
    if (ls.applies)
        std::printf(
            "  walk: the Lambertian series (one trip traced, the others summed: S = %.4g, %.4g, %.4g; quadrature "
            "error bound %.1e relative)\n",
            ls.gain.x, ls.gain.y, ls.gain.z, ls.relative_error);
    else
        std::printf("  walk: every trip traced (no Lambertian series: %s)\n", ls.reason.c_str());
    std::printf("ok: %s is a valid stack\n", operands[0].c_str());
    return 0;
}

}   // namespace

Command check_command() {
    return {"check", "STACK.toml", "parse and validate a stack file, print it and which walk simulate runs on it, exit",
            "", invocation(&no_options, &run_check)};
}

}   // namespace gonio
