// incidence.h: the incident direction as the walk's kernels and its CPU twin get it, written once: the sines and
// cosines of theta_i and phi_i (degrees) computed in double and rounded to float (WalkPush, WalkAngle), from which
// bins.glsl's incident_travel builds the direction (0 and 1 exactly at phi_i = 0: the plane of incidence's bits).
#pragma once
#include <cmath>

namespace gonio {

struct IncidentTrig {
    float sin_ti, cos_ti, sin_pi, cos_pi;
};

inline IncidentTrig incident_trig(double theta_i_deg, double phi_i_deg) {
    const double ti = theta_i_deg * M_PI / 180.0, pi = phi_i_deg * M_PI / 180.0;
    return {float(std::sin(ti)), float(std::cos(ti)), float(std::sin(pi)), float(std::cos(pi))};
}

}   // namespace gonio
