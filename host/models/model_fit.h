// model_fit.h: the values of a model's stack keys that bring it closest to the reference (gonio fit). The model
// sees the stack with its free keys changed; at every step its bins are recomputed exactly as compare computes them
// (ModelEvaluator), and Levenberg-Marquardt minimises the loss over the bins of every incident angle. The standard
// errors propagate the reference's own noise (its bins' standard errors) through the linearised fit.
#pragma once
#include "compare.h"
#include "model_evaluator.h"
#include "stack_vocabulary.h"

#include <string>
#include <vector>

namespace gonio {

// A free key: `layer.N.KEY` (N from 1, top to bottom, a key of that layer's kind), a key of the stack itself
// (exterior_ior), or `param.NAME`, a parameter of the model's own (its file's `parameter:` lines). An RGB key is
// fitted as one value, the same in every channel (`layer.N.KEY`), or one channel of it alone (`layer.N.KEY.r`, `.g`,
// `.b`: the other channels keep the stack's values; three such keys fit the three channels).
struct FitKey {
    std::string name;   // as given
    int layer = -1;   // 0-based; -1: a key of the stack
    const LayerKey* key = nullptr;   // the layer's key
    int channel = -1;   // an RGB key's one channel (0, 1, 2: r, g, b); -1: the same value in every channel
    const StackKey* stack_key = nullptr;   // the stack's key
    int parameter = -1;   // >= 0: the model's parameter of this index (its header's order), not a key of the stack
    double parameter_default = 0;   // its default, where the fit starts unless told
    const ModelFileHeader* model_header = nullptr;   // a parameter's model's header (it outlives the fit)
    ParameterRange range{0.0f, 0.0f};   // the values the stack takes (a roughness also 0: smooth)
    // its value in s (an RGB key fitted as one value: the mean of the channels; a parameter: its default)
    double get(const Stack& s) const;
    void set(Stack& s, double v) const;   // a parameter: nothing (set_parameter)
    // a parameter's value v into the model's parameters (o.parameters[the model's id], the defaults where unset)
    void set_parameter(ModelOptions& o, double v) const;
    // what the fit changes of an RGB key: "r", "g", "b", or "rgb" (one value in every channel); "" for a number
    std::string channels() const;
};

// Throws std::invalid_argument with the reason for a key the stack has not, or its layer's kind does not take, or a
// parameter the model (its header: h) does not have.
FitKey parse_fit_key(const Stack& s, const std::string& text, const ModelFileHeader* h = nullptr);

// log: gonio's remapped error, the mean over cells and channels of (g(model) - g(reference))^2, g(f) = log(1 +
// sqrt f) (compare's RMSE, squared); cosine: the cosine-weighted L2 distance of f, the mean of (f_model -
// f_reference)^2 times each cell's projected solid angle; chi2: the mean of ((model - reference) / se)^2 over the cells.
enum class FitLoss { Log, Cosine, Chi2 };
const char* to_string(FitLoss l);

struct FitOptions {
    std::string model;   // a registry id
    std::vector<FitKey> free;
    // where the fit starts: one or more points, each a value per free key (the stack's own value where not given);
    // from several, each descends and the lowest loss is kept (a loss with several minima)
    std::vector<std::vector<double>> starts;
    FitLoss loss = FitLoss::Log;
    int max_iterations = 40;
    ModelOptions models;   // the evaluator's (Belcour's tables)
    bool progress = false;   // a line per iteration on stderr
    // the second descent over planned cells and the log residual's curvature correction (docs/MODELS.md, "Fitting a
    // model"); false takes both away, the fit as it was biased by about one standard error: a negative control for
    // the calibration test (tests/fit_calibration_test.py), never for a user
    bool bias_corrections = true;
};

struct FitParameter {
    std::string name;
    double start = 0, value = 0;
    double se = 0;   // the reference's noise through the linearised fit; 0 where unconstrained
    bool constrained = true;   // false: the loss does not change with it at the optimum (no standard error)
    bool at_limit = false;   // the optimum is at the end of the key's range
    std::string channels;   // FitKey::channels
};

struct FitResult {
    std::vector<FitParameter> parameters;
    std::vector<std::vector<double>> correlation;   // of the constrained parameters' estimates (1 on the diagonal)
    double loss_start = 0, loss_best = 0;
    int iterations = 0, evaluations = 0;   // the kept descent's iterations; evaluations over all starts
    size_t starts = 1;   // starting points descended from (FitOptions::starts)
    std::string stopped;   // why the kept descent's iterations ended
    Stack best_stack;
    ModelSlices start_bins, best_bins;   // the model at the start and at the optimum
};

// A fit as its user names it (gonio fit's --model, --free, --start, --loss; a sweep file's [[fit]])
struct FitSpec {
    std::string model;   // a registry id
    std::vector<std::string> free;   // layer.N.KEY or a stack key
    // KEY = values, for some of the free keys: one value each, or several (the fit then starts from every
    // combination of them and keeps the lowest loss)
    std::vector<std::pair<std::string, std::vector<double>>> start;
    FitLoss loss = FitLoss::Log;
    bool bias_corrections = true;   // FitOptions::bias_corrections
};
// "log", "cosine" or "chi2"; throws std::invalid_argument otherwise
FitLoss parse_fit_loss(const std::string& text);

// The FitOptions of `spec` on stack s, checked before any work (the others start at the stack's own value). The
// model is a built-in id or the id of one of `user_models` (model files, which the fit's evaluations then run).
// Throws std::invalid_argument with the reason: no such model, a key the stack has not or its layer's kind does not
// take, a start not one of the free keys or outside the key's range, a model that cannot represent the stack at the
// start.
FitOptions fit_options_for(const Stack& s, const FitSpec& spec,
                           const std::vector<std::shared_ptr<const UserModel>>& user_models = {});

// Throws std::invalid_argument where the model cannot represent the stack at the start (with its reason).
FitResult fit_model(ModelEvaluator& ev, const SimResult& ref, const Stack& stack, const FitOptions& o);

}   // namespace gonio
