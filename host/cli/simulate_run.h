// simulate_run.h: the case that simulate, compare and fit run, set up from the walk's options (the output directory,
// --resume, the checkpoints).
#pragma once
#include "case.h"
#include "common_options.h"

#include <string>
#include <vector>

namespace gonio {

// The one stack file of the operands, parsed (`cmd` names the command in the refusal).
Stack stack_operand(const std::string& cmd, const std::vector<std::string>& operands);
// The run of `w` on s: with --resume, the options not given taken from the state it reads and those given checked
// against it; its options checked (--rse's default cap),
// the output directory made and the checkpoints set up. A refusal exits 2 before any work.
Case prepare_run(const WalkSettings& w, Stack s);
// The same run planned (its options taken and checked, the state it resumes read), writing nothing: prepare_run
// without the directory and the checkpoints (the Python module's runs, which write no file unless asked).
Case plan_run(const WalkSettings& w, Stack s);

}   // namespace gonio
