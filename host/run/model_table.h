// model_table.h: the models' scores on the console (compare, score, simulate with models), in 120 columns.
#pragma once
#include "comparison.h"

#include <vector>

namespace gonio {

// One row per scored model, one column per incident angle and side (the RMSE of log(1 + sqrt f), marked within the
// reference's noise, best and tied), wrapped into blocks of columns so that no line is longer than 120 characters;
// then, wrapped too, the models that do not apply or cannot be scored and why, what a user's model claims beside
// what gonio measured of it, and one line for the models --models left out.
void print_model_metrics(const SimResult& ref, const std::vector<ModelSlices>& models, const Comparison& c);

}   // namespace gonio
