#include "cmd_models.h"
#include "artist_parameters.h"
#include "model_applicability.h"
#include "models.h"
#include "options.h"
#include "stack.h"

#include <cstdio>

namespace gonio {

namespace {

// gonio models STACK: each production model's parameters for the stack, what an artist would set
int print_artist_parameters(const std::string& path) {
    const Stack s = parse_stack_file(path);
    std::printf("what an artist would set for %s (each model's own parameters; docs/MODELS.md):\n", path.c_str());
    for (size_t i = 0; i < model_registry().size(); ++i) {
        const ModelInfo& m = model_registry()[i];
        if (m.header.mapping.empty() || m.convention != 0) continue;   // a variant takes its model's parameters
        const std::string reason = model_cannot_represent(i, s);
        if (!reason.empty()) {
            std::printf("%-26s cannot represent it: %s\n", m.id.c_str(), reason.c_str());
            continue;
        }
        std::printf("%-26s %s\n", m.id.c_str(), format_artist_parameters(artist_parameters(m.id, s)).c_str());
    }
    return 0;
}

int run_models(NoSettings&, const std::vector<std::string>& operands) {
    if (operands.size() > 1) usage_error("models takes at most one stack file, got " + std::to_string(operands.size()));
    if (operands.size() == 1) return print_artist_parameters(operands[0]);
    for (size_t i = 0; i < model_registry().size(); ++i) {
        const ModelInfo& m = model_registry()[i];
        std::printf("%-26s %s\n%-26s   %s\n%-26s   represents: %s; %s\n%-26s   %s%s\n", m.id.c_str(),
                    m.citation.c_str(), "", m.summary.c_str(), "", m.represents.c_str(),
                    m.reciprocal ? "reciprocal" : "not reciprocal", "",
                    m.energy_conserving ? "energy-conserving" : "not energy-conserving by construction: ",
                    m.energy_conserving ? "" : m.energy_note.c_str());
        if (!m.header.mapping.empty())
            std::printf("%-26s   its parameters for a stack: %s\n", "", m.header.mapping.c_str());
        for (const ModelParameter& p : m.header.parameters)   // its own (a fit's param.NAME)
            std::printf("%-26s   parameter param.%s: default %g, range [%g, %g]%s%s\n", "", p.name.c_str(), p.value,
                        p.lo, p.hi, p.meaning.empty() ? "" : ": ", p.meaning.c_str());
    }
    return 0;
}

}   // namespace

Command models_command() {
    return {"models", "[STACK]",
            "list the models: id, citation, which stacks each can represent, whether each is reciprocal and "
            "energy-conserving by construction, and a production model's parameters for a stack (what an artist "
            "would set); with a STACK file, each production model's parameters for that stack, as numbers (or why "
            "it cannot represent it)",
            "", invocation(&no_options, &run_models)};
}

}   // namespace gonio
