// gonio-model: one-sided-fresnel
// A header of its id alone: gonio runs it on every stack and measures its reciprocity and energy. Not reciprocal on
// purpose, the base scaled by the coat's transmission on the light's side only.
#include "fresnel.glsl"

vec3 model_f(vec3 l, vec3 v) {
    if (l.z <= 0.0 || v.z <= 0.0) return vec3(0.0);
    GonioLayer coat = gonio_layer(0u);
    GonioLayer base = gonio_layer(1u);
    return (1.0 - fresnel_dielectric(l.z, coat.eta)) * base.albedo / 3.14159265358979;
}
