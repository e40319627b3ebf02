// gonio-model: nan-test
// citation: gonio's tests: NaN for v.x > 0.5, -1 for v.y > 0.8, else 1 / pi
// represents: any
// reciprocal: no
// energy-conserving: yes
vec3 model_f(vec3 l, vec3 v) {
    if (v.x > 0.5) return vec3(0.0 / 0.0);
    if (v.y > 0.8) return vec3(-1.0);
    return vec3(0.318309886);
}
