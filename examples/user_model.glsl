// gonio-model: schlick-coat
// citation: an engine-style clear coat, as many real-time renderers write it: a GGX coat with Schlick's Fresnel
//   (Schlick 1994) over a Lambertian base scaled by the coat's transmission (1 - F) both ways and Beer-Lambert
//   along the refracted directions. An example of a model written as one file (docs/MODELS.md, "Your own model")
// represents: coat-over-lambertian
// reciprocal: yes
// energy-conserving: no (Schlick's F, and the base is not attenuated by what the coat reflects back down)
//
// gonio compare stacks/plastic.toml --model examples/user_model.glsl --theta-i 0,30,60,80 --out out/schlick-coat
//
// f(l, v) in 1/sr, cosine excluded; z is the stack normal, l and v point away from the surface. The stack comes
// from gonio_layer(i) (0: the top layer), the reference's GGX functions from ggx.glsl.
#include "ggx.glsl"

float schlick(float c, float f0) { return f0 + (1.0 - f0) * pow(1.0 - c, 5.0); }

vec3 model_f(vec3 l, vec3 v) {
    if (l.z <= 0.0 || v.z <= 0.0) return vec3(0.0);
    GonioLayer coat = gonio_layer(0u);
    GonioLayer base = gonio_layer(1u);
    float eta = coat.ior.x / gonio_exterior_ior();
    float f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
    float a = max(coat.roughness, 1e-4);
    vec3 h = normalize(l + v);
    float specular = schlick(dot(l, h), f0) * ggx_D(h, a) * ggx_G2(l, v, a) / (4.0 * l.z * v.z);
    // cosines inside the coat (Snell), for the absorption along the two crossings
    float cl = sqrt(1.0 - (1.0 - l.z * l.z) / (eta * eta)), cv = sqrt(1.0 - (1.0 - v.z * v.z) / (eta * eta));
    vec3 absorbed = exp(-coat.optical_depth * (1.0 / cl + 1.0 / cv));
    float through = (1.0 - schlick(l.z, f0)) * (1.0 - schlick(v.z, f0));
    return vec3(specular) + through * absorbed * base.albedo / 3.14159265358979;
}
