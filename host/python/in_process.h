// in_process.h: gonio's commands inside another process (the Python module, module.cpp): their options parsed by
// the commands' own tables (common_options.h) with their refusals, the same pipeline (host/run: run_case,
// models_on_case), the results kept in memory. Nothing is written unless asked (save_run); nothing exits the
// process: a refusal throws (UsageError, RequestRefused, StackError, std::invalid_argument).
#pragma once
#include "bin_nodes.h"
#include "case.h"
#include "image.h"
#include "spectral_output.h"
#include "vk_context.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace gonio {

// A run in memory: the stack and options as the command planned them, and what it computed.
struct InProcessRun {
    Case planned;   // out: "" (no files)
    CaseResult result;
    int device_index = -1;   // the device it ran on (--device), where its models and fits run
};

// Called after every dispatch with the paths traced and the run's total (SimOptions::on_progress); a throw stops the
// run (Ctrl-C in Python).
using RunProgress = std::function<void(uint64_t done, uint64_t total)>;

// The reference of s with `args` (simulate's walk options as on its command line, the stack file left out). The
// options that write files (--out, --resume, --checkpoint-seconds) are refused: save_run writes a run's files.
// With `compare`, also compare's model options (--models, --model FILE, --no-belcour-tables), and the models run on
// the reference's bins and are compared with it, as `gonio compare` does.
InProcessRun run_in_process(const Stack& s, const std::vector<std::string>& args, bool compare,
                            const RunProgress& progress);

// simulate --spectral in memory: args are simulate's walk options and --bands, --band-points, --band-paths (the
// same refusals: --phi-i, --resume and --max-seconds); the run as write_spectral_exr and write_spectral_summary take
// it. progress: as run_in_process's, over the passes' batch.
SpectralResult spectral_in_process(const Stack& s, const std::vector<std::string>& args, const RunProgress& progress);

// gonio render in memory: args are render's options (not --out, --reference or --spectral); the table is traced
// now, its two halves as render traces them. The images as render writes them: the reference, its halves, and each
// model that renders (the others in not_rendered, with the reason).
struct InProcessRender {
    std::vector<std::pair<std::string, Image>> images;   // "reference", "reference-half-a", "-half-b", then the models
    std::vector<std::pair<std::string, std::string>> not_rendered;   // model id, why
    std::string environment;   // its name and source
};
// progress: while the table is traced.
InProcessRender render_in_process(const Stack& s, const std::vector<std::string>& args, const RunProgress& progress);

// The models that `args` selects (compare's model options) on the bins of `run`, and `extra` (models given as
// values: node_model) beside them, compared with its reference: the run with those models (its own replaced). The
// built-in models run where args are given or no extra is (then all of them, as compare runs them). `glsl`: models
// as GLSL text (a model file's, docs/MODELS.md "Your own model"), compiled as --model FILE is and run beside the ids
// of --models (alone where no args are given).
InProcessRun with_models(const InProcessRun& run, const std::vector<std::string>& args,
                         std::vector<ModelSlices> extra = {}, const std::vector<std::string>& glsl = {});

// Where a model given as values is evaluated on run's bins: k x k nodes per bin (gonio nodes --nodes-per-bin k).
// Refuses k outside 1 to 16 and a node count gonio nodes refuses.
std::vector<BinNode> run_nodes(const InProcessRun& run, int k);
// That model's bins from its values at run_nodes(run, k), as gonio score makes them; `id` checked as score checks
// --id.
ModelSlices node_model(const InProcessRun& run, const std::string& id, int k, const std::vector<glm::dvec3>& values);

// `gonio fit --reference` on run in memory: args are the fit's own options (--model ID|FILE.glsl, --free, --start,
// --loss); the run with the model at the start (its id) and at the fit (ID@fit) beside the reference, and fit.json's
// bytes (the stack named as the run's file, as `gonio fit STACK` names it).
struct InProcessFit {
    InProcessRun run;
    std::string fit_json;
};
InProcessFit fit_in_process(const InProcessRun& run, const std::vector<std::string>& args);

// summary.json's and slices.csv's bytes, and every file of the run written to dir (the EXR, slices.csv,
// summary.json, state.gonio: what `gonio compare` / `gonio simulate --out dir` write).
std::string run_summary_text(const InProcessRun& run);
std::string run_slices_text(const InProcessRun& run);
void save_run(const InProcessRun& run, const std::string& dir);

// A command's `gonio CMD --help` text.
std::string command_help_text(const std::string& command);

}   // namespace gonio
