// gonio-model: ww-corrected-delta
// citation: Bati, Pacanowski & Barla 2019, Equation 4, as tests/user_models/ww_corrected_rewrite.glsl, with a smooth
//   coat's reflection as what it is, a delta lobe in the mirror direction whose weight is the Fresnel reflectance
//   F(cos theta_i), announced by model_lobes and left out of model_f; a rough coat's reflection lobe is announced too
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
    float top = 0.0;   // a smooth coat's: the delta lobe (model_lobes)
    if (coat.roughness > 0.0) {
        vec3 h = normalize(l + v);
        float a = coat.roughness;
        top = fresnel_dielectric(dot(l, h), eta) * ggx_D(h, a) * ggx_G2(l, v, a) / (4.0 * l.z * v.z);
    }
    vec3 through = exp(-coat.optical_depth * (1.0 / max(cos_inside(l.z, eta), 1e-6) +
                                              1.0 / max(cos_inside(v.z, eta), 1e-6)));
    float t = (1.0 - fresnel_dielectric(l.z, eta)) * (1.0 - fresnel_dielectric(v.z, eta)) / (eta * eta);
    return vec3(top) + t * base.albedo * (1.0 / 3.14159265358979) * through;
}

uint model_lobes(vec3 l, out GonioLobe lobes[GONIO_MAX_LOBES]) {
    GonioLayer coat = gonio_layer(0u);
    float F = fresnel_dielectric(l.z, coat.ior.x / gonio_exterior_ior());
    lobes[0] = GonioLobe(vec3(-l.x, -l.y, l.z), coat.roughness, vec3(F));
    return 1u;
}
