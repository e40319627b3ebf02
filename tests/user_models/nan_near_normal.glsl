// gonio-model: nan-near-normal
// citation: gonio's tests: NaN where the light is within about 18 degrees of the normal, else 0.5 / pi
// represents: any
// reciprocal: no
// energy-conserving: yes
vec3 model_f(vec3 l, vec3 v) {
    if (l.z > 0.95) return vec3(0.0 / 0.0);
    return vec3(0.159154943);
}
