// gonio-model: heavy-loop
// citation: gonio's tests: 400 loop trips per evaluation (lavapipe's loop limiter: 65535 trips per invocation in
//   all), f = 1 / pi in the end
// represents: any
// reciprocal: yes
// energy-conserving: yes
vec3 model_f(vec3 l, vec3 v) {
    float s = 0.0;
    for (uint i = 0u; i < 400u * gonio_layer_count() / 2u; ++i) s += 1.0 / 400.0;
    return vec3(s * 0.318309886 * 2.0 / float(gonio_layer_count()));
}
