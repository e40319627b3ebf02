// simulate_run.h: the reference's run that simulate and compare share: set up from the walk's options (the output
// directory, --resume, the checkpoints), and its files and lines (EXR, slices.csv, summary.json, state.gonio).
#pragma once
#include "common_options.h"
#include "compare.h"
#include "json.h"
#include "reference.h"
#include "stack.h"

#include <optional>
#include <string>
#include <vector>

namespace gonio {

struct SimulateRun {
    Stack stack;
    SimOptions sim;   // checked, the checkpoints written into out
    std::string out;
    std::optional<SimResult> previous;   // --resume DIR: the run it continues
    const SimResult* resumed() const { return previous ? &*previous : nullptr; }
};

// The one stack file of the operands, parsed (`cmd` names the command in the refusal).
Stack stack_operand(const std::string& cmd, const std::vector<std::string>& operands);
// The run of `w` on s: with --resume, the options not given taken from the state it reads and those given checked
// against it; its options checked (--rse's default cap),
// the output directory made and the checkpoints set up. A refusal exits 2 before any work.
SimulateRun prepare_run(const WalkSettings& w, Stack s);
// Writes the run's files (with the models' rows and metrics when `models`), prints a line per incident angle and
// the models' metrics. Returns 1 where something could not be used (paths whose weight stopped being finite, a
// model's values, numbers of summary.json), else 0.
int write_run(const SimulateRun& run, const SimResult& r, const std::vector<ModelSlices>* models,
              const Json* models_summary);

}   // namespace gonio
