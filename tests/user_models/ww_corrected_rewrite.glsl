// gonio-model: ww-corrected-rewrite
// citation: Bati, Pacanowski & Barla 2019, Equation 4, written again from the paper for gonio's tests (not from
//   shaders/lib/models/builtin/02-ww-corrected.glsl): it must give the built-in model's bins
// represents: coat-over-lambertian
// reciprocal: yes
// energy-conserving: yes
#include "ggx.glsl"
#include "fresnel.glsl"

// cos theta inside a coat of relative index eta, by Snell's law
float cos_inside(float c, float eta) { return sqrt(max(0.0, 1.0 - (1.0 - c * c) / (eta * eta))); }

vec3 model_f(vec3 l, vec3 v) {
    if (l.z <= 0.0 || v.z <= 0.0) return vec3(0.0);
    GonioLayer coat = gonio_layer(0u);
    GonioLayer base = gonio_layer(1u);
    float eta = coat.ior.x / gonio_exterior_ior();
    float a = max(coat.roughness, 1e-4);   // a smooth coat as the built-in models take it
    vec3 h = normalize(l + v);
    float top = fresnel_dielectric(dot(l, h), eta) * ggx_D(h, a) * ggx_G2(l, v, a) / (4.0 * l.z * v.z);
    vec3 through = exp(-coat.optical_depth * (1.0 / max(cos_inside(l.z, eta), 1e-6) +
                                              1.0 / max(cos_inside(v.z, eta), 1e-6)));
    float t = (1.0 - fresnel_dielectric(l.z, eta)) * (1.0 - fresnel_dielectric(v.z, eta)) / (eta * eta);
    return vec3(top) + t * base.albedo * (1.0 / 3.14159265358979) * through;
}
