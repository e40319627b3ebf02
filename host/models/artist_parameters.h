// artist_parameters.h: what an artist would set in a production model for a physical stack (each model's mapping,
// the GONIO_MODEL_ARTIST_PARAMETERS hook in its own file, run through the CPU twin, and the names of its header's
// `artist-parameters:` lines; docs/MODELS.md "what an artist would set"), for `gonio models STACK`.
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
// the models whose file maps a stack to them (`artist-parameters:` lines; a variant by its base's). A spectral
// comparison evaluates these in RGB, as they are defined (docs/SPECTRAL.md). False for a user's model (not in the
// registry), which takes the stack itself.
bool model_takes_artist_colours(const std::string& model_id);

// The parameters of a production model (a variant: its base's) for a stack of a shape its `artist-parameters:` lines
// name: one dielectric coat over a Lambertian, a conductor, or a dielectric interface over a Lambertian. Empty for a
// model without a mapping (the research models take the stack itself). Throws std::invalid_argument for a stack of
// another shape or an unknown id, std::logic_error where the file's hook gives another count than its line names.
std::vector<ArtistParameter> artist_parameters(const std::string& model_id, const Stack& s);

// "name value, name (r, g, b), ..." in the model's order
std::string format_artist_parameters(const std::vector<ArtistParameter>& parameters);

}   // namespace gonio
