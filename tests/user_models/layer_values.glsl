// gonio-model: layer-values
// citation: gonio's tests: f is a constant made of the stack's values as gonio_layer() gives them
// represents: any
// reciprocal: yes
// energy-conserving: no (a test of the stack's accessors)
vec3 model_f(vec3 l, vec3 v) {
    GonioLayer a = gonio_layer(1u), b = gonio_layer(2u);
    return vec3(a.ior.x + 10.0 * float(gonio_layer_count()), b.ior.y + 10.0 * gonio_exterior_ior(),
                b.k.z + 10.0 * a.optical_depth.z + 100.0 * a.roughness);
}
