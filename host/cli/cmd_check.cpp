#include "cmd_check.h"
#include "stack_gpu.h"
#include "stack.h"
#include "stack_spectral.h"

#include <cstdio>

namespace gonio {

namespace {

int run_check(NoSettings&, const std::vector<std::string>& operands) {
    if (operands.size() != 1) usage_error("check takes one stack file");
    Stack s = parse_stack_file(operands[0]);
    std::printf("%s", describe_stack(s).c_str());
    // which walk simulate runs on it (docs/PHYSICS.md, "The Lambertian series")
    const LambertianSeries ls = walk_stack(s, true).series;
    if (ls.applies)
        std::printf(
            "  walk: the Lambertian series (one trip traced, the others summed: S = %.4g, %.4g, %.4g; quadrature "
            "error bound %.1e relative)\n",
            ls.gain.x, ls.gain.y, ls.gain.z, ls.relative_error);
    else
        std::printf("  walk: every trip traced (no Lambertian series: %s)\n", ls.reason.c_str());
    // what a spectral run makes of the keys given per RGB channel (docs/SPECTRAL.md)
    for (const KeyUplift& u : stack_uplifts(s)) {
        const std::array<double, 3> a = u.uplift.spectrum.per_nm();
        std::printf(
            "  spectral run: layer %zu's %s [%g, %g, %g] %s: s(nm) = S(%.9g nm^2 %+.9g nm %+.9g) (Jakob & "
            "Hanika 2019), %s (CIE76 %.2g)\n",
            u.layer + 1, u.key.c_str(), u.given.x, u.given.y, u.given.z,
            u.through_transmittance ? "uplifted through its transmittance exp(-optical_depth) = s"
                                    : "uplifted to the spectrum",
            a[0], a[1], a[2], u.uplift.reached ? "its colour reached" : "refused: its colour is not reached",
            u.uplift.delta_e76);
    }
    std::printf("ok: %s is a valid stack\n", operands[0].c_str());
    return 0;
}

}   // namespace

Command check_command() {
    return {"check", "STACK.toml", "parse and validate a stack file, print it and which walk simulate runs on it, exit",
            "", invocation(&no_options, &run_check)};
}

}   // namespace gonio
