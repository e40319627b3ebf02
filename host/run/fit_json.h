// fit_json.h: gonio fit's result as fit.json, and on the console.
#pragma once
#include "comparison.h"
#include "json.h"
#include "model_fit.h"

#include <string>

namespace gonio {

// fit.json of the fit f of spec's model to the reference r of `stack`, and its lines on the console; c: the
// comparison of the model at the start (its first model) and at the fit (its second) with r.
Json fit_json(const FitSpec& spec, const std::string& stack, const SimResult& r, const FitResult& f,
              const Comparison& c);

}   // namespace gonio
