// cmd_simulate.h: `gonio simulate` and `gonio compare`: the reference on a stack, and with compare every model on
// the same bins; EXR, slices.csv, summary.json, state.gonio, and compare's figures and report.html.
#pragma once
#include "args.h"

namespace gonio {

int cmd_simulate(const Args& a, bool compare);

}   // namespace gonio
