#include "model_applicability.h"
#include "model_plan.h"
#include "model_registry.h"
#include "model_twin.h"

namespace gonio {

std::string model_cannot_represent(size_t index, const Stack& s) {
    const std::string& id = model_registry().at(index).id;
    const ModelInfo& info = model_registry().at(index);
    // a variant represents what its base model does; the models gonio plans (model_plan.h) have their own reasons
    // below, any other built-in model (integrated as a black box) represents the stack shapes of its header, as a
    // user's model
    const PlanKind kind = plan_kind(shader_model_of(index));
    if (kind == PlanKind::BlackBox) return model_file_cannot_represent(info.header, s);
    // A scattering medium: Belcour 2018's operators take one that scatters forward (its variance is defined for
    // g in (0, 1]); tm21's two-flux tm2 and the other models have no scattering medium and would read its optical
    // depth as absorption alone.
    for (size_t i = 0; i < s.layers.size(); ++i) {
        if (!s.medium_scatters(i)) continue;
        const std::string layer = "layer " + std::to_string(i + 1) + "'s medium scatters";
        if (is_belcour(index)) {
            if (!(s.layers[i].phase_g > 0.0f))
                return id + " takes forward-scattering media only (" + layer + " with phase_g " +
                       std::to_string(s.layers[i].phase_g) +
                       "): its Henyey-Greenstein variance ((1 - g) / g)^0.8 / (1 + g) is defined for g in (0, 1] "
                       "(Belcour 2018 section 5)";
            continue;
        }
        if (kind == PlanKind::Tm21Lobes)
            return id + ": the authors' two-flux tm2 takes no medium (" + layer +
                   "); their six-flux tm6 has Henyey-Greenstein media, not implemented";
        return id + " has no scattering medium (" + layer +
               ": its single-scattering albedo is above 0); it would take the optical depth as absorption alone";
    }
    if (kind == PlanKind::Tm21Lobes) {
        for (const Layer& L : s.layers)
            if (L.kind == InterfaceKind::Lambertian)
                return id +
                       " (two-flux, tm2) takes dielectric interfaces over a conductor; a Lambertian base needs the "
                       "authors' six-flux variant, not implemented";
        if (s.transmissive()) return id + ": the transmissive variant (the authors' tm2_dielectric) is not implemented";
        return "";
    }
    if (is_belcour(index)) {
        for (const Layer& L : s.layers)
            if (L.kind == InterfaceKind::Lambertian)
                return id +
                       " is limited to forward propagation: light entering a Lambertian base never leaves it on "
                       "reflection (Bati et al. 2019 section 2.2)";
        if (s.transmissive()) {
            if (kind == PlanKind::BelcourSymmetric)
                return id +
                       " is defined for reflection (its statistics use the reflection half-vector); this stack "
                       "is transmissive";
            if (s.base().ior.x != s.exterior_ior)
                return id +
                       ": a transmitted lobe into a substrate of another IOR than the exterior's is not "
                       "implemented (only slabs: substrate IOR " +
                       std::to_string(s.base().ior.x) + " differs from the exterior's " +
                       std::to_string(s.exterior_ior) + ")";
        }
        // the TIR convention differs only below an absorbing medium: elsewhere the variant is its base model, and is
        // not computed twice
        if (info.convention & MODEL_CONVENTION_TIR_BELOW_MEDIA) {
            bool absorbing = false;
            for (size_t i = 0; i + 1 < s.layers.size(); ++i) absorbing |= s.layers[i].optical_depth != glm::vec3(0.0f);
            if (!absorbing)
                return id + " equals " + id.substr(0, id.size() - 4) +
                       " on this stack: no absorbing medium lies below an "
                       "interface, where keeping the TIR term differs";
        }
        return "";
    }
    if (s.transmissive())
        return id + " models reflection only (a BRDF); this stack is transmissive (its last layer is a dielectric)";
    if (s.base().kind != InterfaceKind::Lambertian && s.base().kind != InterfaceKind::Conductor)
        return id + " takes a Lambertian or conductor base (models/common.glsl base_brdf), not a " +
               to_string(s.base().kind);
    if (s.layers.size() != 2)
        return id + " is implemented for one dielectric coat over an opaque base; this stack has " +
               std::to_string(s.layers.size()) + " layers";
    return "";
}

}   // namespace gonio
