// artist_parameters.h: what an artist would set in a production model for a physical stack (the numbers of each
// model's `mapping:` header line, docs/MODELS.md "what an artist would set"), and the stack a set of those
// parameters stands for (the inverse), for `gonio models STACK` and the round-trip test.
#pragma once
#include "stack.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gonio {

struct ArtistParameter {
    std::string name;   // as the model's definition spells it (coat_ior, clearcoatRoughness, ...)
    glm::vec3 value{0.0f};   // a colour per channel; a scalar in all three
    bool colour = false;
};

// Whether a model's inputs are an artist's parameters, colours among them (base colour, F0, specular colour, F82 tint):
// the production models artist_parameters maps (a variant by its base's id). A spectral comparison evaluates these in
// RGB, as they are defined (docs/SPECTRAL.md).
bool model_takes_artist_colours(const std::string& model_id);

// The parameters of a production model (gltf-clearcoat, openpbr, openpbr-adobe, enterprise-pbr, standard-surface,
// materialx-layer, cycles-principled, interfaced-lambertian; a variant by its base's id) for a stack it represents (model_cannot_represent empty): one
// dielectric coat over a Lambertian or a conductor. Empty for a model without a mapping (the research models take
// the stack itself). Throws std::invalid_argument for a stack of another shape.
std::vector<ArtistParameter> artist_parameters(const std::string& model_id, const Stack& s);

// The stack those parameters stand for, in an exterior of IOR exterior_ior: the inverse of artist_parameters. Where
// a model's parameters hold less than the stack (glTF's and Enterprise PBR's metal: F0 alone), the conductor of that
// F0 with k = 0 (one of many: the parameters of the result are the same). Throws std::invalid_argument for a
// missing parameter.
Stack stack_from_artist_parameters(const std::string& model_id, const std::vector<ArtistParameter>& parameters,
                                   float exterior_ior);

// "name value, name (r, g, b), ..." in the model's order
std::string format_artist_parameters(const std::vector<ArtistParameter>& parameters);

}   // namespace gonio
