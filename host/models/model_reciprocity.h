// model_reciprocity.h: a model's reciprocity, measured: f(l, v) against f(v, l) at direction pairs over the
// reflection hemisphere (a user's model through models.comp KERNEL 3; the built-in models are measured the same way
// by the tests, through their CPU twin, tests/test_models.cpp ModelsReciprocity).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace gonio {

// Below this largest relative asymmetry a model is reciprocal as far as float evaluation can tell (the tests' bound
// for the built-in models that claim it).
constexpr double kReciprocityTolerance = 1e-4;

// The pairs: l and v over theta 5 to 88 degrees (7 each) and 4 azimuths between them, l in the x-z plane; each
// pair (l, v) is followed by its swap (v, l): 2 x 196 evaluations.
std::vector<glm::vec3> reciprocity_directions();   // l0, v0, v0, l0, l1, v1, ...

struct ModelAsymmetry {
    uint32_t pairs = 0;   // pairs compared (0: not measured)
    uint32_t non_finite = 0;   // pairs where either value was NaN, infinite or negative (left out)
    uint32_t compared = 0;   // pair-channels compared: those whose mean is above 1e-6 of the largest value (0: f is
        // 0 at every pair, and reciprocity untested)
    double worst = 0;   // the largest |f(l, v) - f(v, l)| / mean of the two over channels whose mean is above
        // 1e-6 of the largest value
    double theta_l = 0, theta_v = 0, phi = 0;   // where (degrees; phi the azimuth of v from l's)
    bool reciprocal() const { return compared > 0 && worst < kReciprocityTolerance; }
};

// The asymmetry of values f at reciprocity_directions(), in their order (one f per direction pair: f[2k] = f(l, v),
// f[2k + 1] = f(v, l)).
ModelAsymmetry measure_asymmetry(const std::vector<glm::dvec3>& f);

}   // namespace gonio
