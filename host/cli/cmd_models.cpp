#include "cmd_models.h"
#include "models.h"

#include <cstdio>

namespace gonio {

namespace {

int run_models(NoSettings&, const std::vector<std::string>&) {
    for (size_t i = 0; i < model_registry().size(); ++i) {
        const ModelInfo& m = model_registry()[i];
        std::printf("%-26s %s\n%-26s   %s\n%-26s   represents: %s; %s\n%-26s   %s%s\n", m.id.c_str(),
                    m.citation.c_str(), "", m.summary.c_str(), "", m.represents.c_str(),
                    m.reciprocal ? "reciprocal" : "not reciprocal", "",
                    m.energy_conserving ? "energy-conserving" : "not energy-conserving by construction: ",
                    m.energy_conserving ? "" : m.energy_note.c_str());
        if (!m.header.mapping.empty())
            std::printf("%-26s   its parameters for a stack: %s\n", "", m.header.mapping.c_str());
    }
    return 0;
}

}   // namespace

Command models_command() {
    return {"models", "",
            "list the models: id, citation, which stacks each can represent, whether each is reciprocal and "
            "energy-conserving by construction, and a production model's parameters for a stack (what an artist "
            "would set)",
            "", invocation(&no_options, &run_models)};
}

}   // namespace gonio
