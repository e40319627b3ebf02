// gonio-model: retro-lobe
// citation: gonio's tests. A lobe of width sigma = 0.01 about l itself (retroreflection), which no lobe hint
//   announces. f cos = K exp(-(1 - l.v) / sigma^2), whose integral over the sphere is K 2 pi sigma^2 (1 - e^(-2 /
//   sigma^2)), and K = 1 / (4 pi sigma^2) makes the directional albedo 0.5. 1 - l.v is |v - l|^2 / 2: in float,
//   1 - dot(l, v) next to the peak keeps 3 digits only
// represents: any
// reciprocal: yes
// energy-conserving: yes
const float SIGMA2 = 1e-4;
vec3 model_f(vec3 l, vec3 v) {
    float K = 1.0 / (4.0 * 3.14159265358979 * SIGMA2);
    vec3 d = v - l;
    return vec3(K * exp(-0.5 * dot(d, d) / SIGMA2) / v.z);
}
