// gonio-model: broken
// citation: gonio's tests: line 8 does not compile
// represents: any
// reciprocal: yes
// energy-conserving: yes
vec3 model_f(vec3 l, vec3 v) {
    float x = l.z;
    return vec3(x) * undeclared_thing;
}
