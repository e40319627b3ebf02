// gonio-model: narrow-lobe
// citation: gonio's tests. A lobe of width w = 2e-4 about a direction c (here l itself: retroreflection) that
//   model_lobes announces: f cos = K / (1 + |v - c|^2 / w^2)^2 (GGX-like tails), on c's side of the surface. With
//   |v - c|^2 = 2 (1 - cos gamma) its integral over the sphere is 4 pi K w^2 / (w^2 + 4), and K = (w^2 + 4) / (8 pi
//   w^2) makes it 0.5 (less the tails beyond the horizon, below 1e-7 at 30 and 55 degrees).
//   tests/test_user_model.cpp makes its variants from this text (the centre, no hints, unusable hints).
// represents: any
// reciprocal: no
// energy-conserving: yes
const float W2 = 4e-8;
vec3 lobe_centre(vec3 l) { return l; }
vec3 model_f(vec3 l, vec3 v) {
    vec3 c = lobe_centre(l);
    if (!(c.z * v.z > 0.0)) return vec3(0.0);
    vec3 d = v - c;
    float K = (W2 + 4.0) / (8.0 * 3.14159265358979 * W2);
    float q = 1.0 + dot(d, d) / W2;
    return vec3(K / (q * q) / abs(v.z));
}
uint model_lobes(vec3 l, out GonioLobe lobes[GONIO_MAX_LOBES]) {
    lobes[0] = GonioLobe(lobe_centre(l), 1e-4, vec3(0.0));
    return 1u;
}
