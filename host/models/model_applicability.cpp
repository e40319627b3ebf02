// model_applicability.cpp: which stacks a model of the registry takes, from its file's header (model_file.h: its
// `refuses:` lines, then the shapes it `represents:`), and the variants that equal their base model on a stack.
#include "model_applicability.h"
#include "model_registry.h"

namespace gonio {

std::string model_cannot_represent(size_t index, const Stack& s) {
    const ModelInfo& info = model_registry().at(index);
    std::string why = model_file_cannot_represent(info.header, s, info.id);
    if (!why.empty()) return why;
    // the TIR convention differs only below an absorbing medium, dev_1.2's darkening only under an absorbing coat:
    // elsewhere the variant is the model without its last suffix, and is not computed twice
    const uint32_t only_absorbing = MODEL_CONVENTION_TIR_BELOW_MEDIA | MODEL_CONVENTION_DARKENING_T2;
    if (info.convention & only_absorbing) {
        bool absorbing = false;
        for (size_t i = 0; i + 1 < s.layers.size(); ++i) absorbing |= s.layers[i].optical_depth != glm::vec3(0.0f);
        if (!absorbing)
            return info.id + " equals " + info.id.substr(0, info.id.rfind('+')) +
                   " on this stack: no absorbing medium lies below an interface, where " +
                   (info.convention & MODEL_CONVENTION_TIR_BELOW_MEDIA ? "keeping the TIR term"
                                                                       : "the coat's T^2 in the darkening") +
                   " differs";
    }
    // openpbr's compensation changes only a base's GGX lobes (a metal's, a dielectric base's): over a Lambertian
    // alone +single is openpbr
    if (info.convention & MODEL_CONVENTION_SINGLE_SCATTERING_LOBES) {
        bool base_lobe = false;
        for (size_t i = 1; i < s.layers.size(); ++i) base_lobe |= s.layers[i].kind != InterfaceKind::Lambertian;
        if (!base_lobe)
            return info.id + " equals " + info.id.substr(0, info.id.rfind('+')) +
                   " on this stack: its base has no GGX lobe, the only lobes the energy compensation changes";
    }
    return "";
}

}   // namespace gonio
