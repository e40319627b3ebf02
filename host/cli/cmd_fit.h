// cmd_fit.h: `gonio fit`: the values of a model's stack keys that bring it closest to the reference.
#pragma once
#include "model_fit.h"
#include "options.h"

namespace gonio {

Command fit_command();
// The fit's own options (--model, --free, --start, --loss), which set spec: gonio fit's table without the walk's
// and the files' (the Python module's fit takes them).
OptionTable fit_spec_options(FitSpec& spec);
// spec's model (a FILE.glsl read and compiled: its id) and free keys checked against s before any work: the fit's
// options, or a usage_error with the reason.
FitOptions checked_fit_options(const FitSpec& spec, const Stack& s, bool progress);

}   // namespace gonio
