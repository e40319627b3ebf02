// stack_spectral.cpp: see stack_spectral.h.
#include "stack_spectral.h"
#include "measured_materials.h"
#include "stack_vocabulary.h"
#include "text_format.h"

namespace gonio {

std::string spectral_refusal(const Stack& s) {
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& y = s.layers[i];
        for (const LayerKey* key : keys_of(y.kind)) {
            if (!y.material.empty() && (std::string_view(key->name) == "ior" || std::string_view(key->name) == "k"))
                continue;
            const glm::vec3 v = key->get(y);
            if (v.x != v.y || v.y != v.z)
                return "layer " + std::to_string(i + 1) + "'s " + key->name + " is given per RGB channel ([" +
                       format_shortest(v.x) + ", " + format_shortest(v.y) + ", " + format_shortest(v.z) +
                       "]): a spectral run takes one value for it (the same at every wavelength) or, for a "
                       "conductor, a measured material (material = \"Au\": " +
                       measured_conductor_names() + "); a spectrum made from RGB is not defined yet (docs/SPECTRAL.md)";
        }
    }
    return "";
}

Stack stack_at_wavelengths(const Stack& s, const std::array<double, 3>& nm) {
    Stack out = s;
    for (Layer& y : out.layers) {
        if (y.material.empty()) continue;
        const MeasuredConductor& m = *find_measured_conductor(y.material);
        for (int c = 0; c < 3; ++c) {
            y.ior[c] = float(measured_n(m, nm[size_t(c)]));
            y.k[c] = float(measured_k(m, nm[size_t(c)]));
        }
    }
    return out;
}

}   // namespace gonio
