#include "stack_gpu.h"

namespace gonio {

StackGpu pack_stack(const Stack& s) {
    StackGpu g{};
    g.info = vec4(float(s.layers.size()), 0.0f, 0.0f, 0.0f);
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& L = s.layers[i];
        glm::vec3 above = s.ior_above(i);
        LayerGpu& o = g.layers[i];
        float eta = L.ior.x / above.x;
        o.p0 = vec4(float(int(L.kind)), L.roughness, eta, eta != 0.0f ? 1.0f / eta : 0.0f);
        o.tau = vec4(L.optical_depth, 0.0f);
        if (L.kind == InterfaceKind::Conductor) {
            o.c0 = vec4(L.ior / above, 0.0f);
            o.c1 = vec4(L.k / above, 0.0f);
        } else if (L.kind == InterfaceKind::Lambertian) {
            o.c0 = vec4(L.albedo, 0.0f);
        }
    }
    return g;
}

WalkSpec walk_spec(const Stack& s, bool specialised) {
    WalkSpec w;
    w.specialised = specialised;
    w.layer_count = uint(s.layers.size());
    w.base_kind = uint(int(s.base().kind));
    for (size_t i = 0; i < s.layers.size(); ++i) {
        const Layer& L = s.layers[i];
        if (L.roughness > 0.0f) w.rough_mask |= 1u << i;
        if (L.optical_depth.x > 0.0f || L.optical_depth.y > 0.0f || L.optical_depth.z > 0.0f) w.absorb_mask |= 1u << i;
    }
    return w;
}

}  // namespace gonio
