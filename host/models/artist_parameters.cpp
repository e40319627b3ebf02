#include "artist_parameters.h"

#include "model_registry.h"
#include "model_twin.h"
#include "stack_gpu.h"

#include <cstdio>
#include <stdexcept>

namespace gonio {

namespace {

const ModelInfo& registry_entry(const std::string& id) {
    if (const ModelInfo* m = find_model(id)) return *m;
    throw std::invalid_argument("no built-in model '" + id + "'");
}

// The stack as a mapping reads it (models/common.glsl ArtistValues): the coat and its base with the roughnesses as
// given (0 for a smooth interface), the coat's IOR relative to the exterior; a conductor's n and k, a dielectric
// base's IOR relative to the coat; `diffuse` the Lambertian under a dielectric base
CoatParams mapping_input(const Stack& s, glm::vec3& diffuse) {
    CoatParams p{};
    const Layer &coat = s.layers[0], &base = s.layers[1];
    p.alpha0 = coat.roughness;
    p.eta = coat.ior.x / s.exterior_ior;
    p.tau = coat.optical_depth;
    p.alpha1 = base.roughness;
    diffuse = glm::vec3(0.0f);
    if (base.kind == InterfaceKind::Lambertian) {
        p.base_kind = KIND_LAMBERTIAN;
        p.base_c0 = base.albedo;
    } else if (base.kind == InterfaceKind::Conductor) {
        p.base_kind = KIND_CONDUCTOR;
        p.base_c0 = base.ior / coat.ior.x;
        p.base_c1 = base.k / coat.ior.x;
    } else {
        p.base_kind = KIND_DIELECTRIC;
        p.base_eta = base.ior.x / coat.ior.x;
        diffuse = s.layers[2].albedo;
    }
    return p;
}

std::string shapes_of(const ModelFileHeader& h) {
    std::string out;
    for (const ArtistParameterList& list : h.artist_parameters)
        out += (out.empty() ? "" : ", ") + std::string(to_string(list.shape));
    return out;
}

}   // namespace

bool model_takes_artist_colours(const std::string& model_id) {
    const ModelInfo* m = find_model(model_id);
    return m && !m->header.artist_parameters.empty();   // a user's model (--model FILE) takes the stack itself
}

std::vector<ArtistParameter> artist_parameters(const std::string& model_id, const Stack& s) {
    const ModelInfo& m = registry_entry(model_id);
    const ModelFileHeader& h = m.header;
    if (h.artist_parameters.empty()) return {};
    const ArtistParameterList* list = nullptr;
    for (const ArtistParameterList& l : h.artist_parameters)
        if (stack_has_shape(s, l.shape)) list = &l;
    if (!list)
        throw std::invalid_argument(model_id + " has artist parameters for " + shapes_of(h) +
                                    " (artist-parameters:), not for this stack's shape");
    glm::vec3 diffuse;
    const CoatParams p = mapping_input(s, diffuse);
    ArtistValues a{};
    a.count = 0;
    const std::string where = h.path + ":" + std::to_string(list->line);
    if (!eval_model_artist_parameters_on(m.shader_model, pack_stack(s), p, diffuse, a))
        throw std::logic_error(where + ": artist-parameters, but the file defines no GONIO_MODEL_ARTIST_PARAMETERS");
    if (a.count != list->names.size())
        throw std::logic_error(where + ": artist-parameters names " + std::to_string(list->names.size()) + " for " +
                               to_string(list->shape) + ", its GONIO_MODEL_ARTIST_PARAMETERS gives " +
                               std::to_string(a.count) + " values");
    std::vector<ArtistParameter> out;
    for (size_t i = 0; i < list->names.size(); ++i)
        out.push_back({list->names[i].name, a.value[i], list->names[i].colour});
    return out;
}

std::string format_artist_parameters(const std::vector<ArtistParameter>& ps) {
    std::string out;
    char buf[128];
    for (const ArtistParameter& p : ps) {
        if (p.colour)
            std::snprintf(buf, sizeof buf, "%s (%.4g, %.4g, %.4g)", p.name.c_str(), p.value.x, p.value.y, p.value.z);
        else
            std::snprintf(buf, sizeof buf, "%s %.4g", p.name.c_str(), p.value.x);
        out += (out.empty() ? "" : ", ") + std::string(buf);
    }
    return out;
}

}   // namespace gonio
