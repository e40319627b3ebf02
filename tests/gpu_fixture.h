// gpu_fixture.h: one Vulkan context per test binary, with the Khronos validation layer on; any validation
// message fails the test that produced it.
#pragma once
#include "histogram.h"
#include "reference.h"
#include "stack.h"
#include "vk_context.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace gonio_test {

inline gonio::VkContext& context() {
    static std::unique_ptr<gonio::VkContext> ctx = [] {
        gonio::ContextOptions o;
        o.validation = true;
        return std::make_unique<gonio::VkContext>(o);
    }();
    return *ctx;
}

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override { before_ = context().validation_messages(); }
    void TearDown() override {
        EXPECT_EQ(context().validation_messages(), before_) << "the Vulkan validation layer reported messages";
    }
    uint64_t before_ = 0;
};

// Standard error of a run's reflected + transmitted energy fraction per path (channel c of angle a), from its raw
// sums: a path leaves through one bin at most, so the per-path exit's variance is (sum w^2)/N - ((sum w)/N)^2. The
// full walk's exits weigh at most 1 and a lossless stack returns exactly 1; the Lambertian series' exits can weigh
// more (S times), so its energy fractions are estimates with this noise (docs/PHYSICS.md).
// With the booking estimators (docs/PHYSICS.md) a path books up to 1 + entry branch + exit estimates bins (its own
// exit, the entry's reflected branch, the fresh exit estimates), so that per-path variance leaves out their cross
// terms; by Cauchy-Schwarz the square of a path's total is at most `bookings` times the sum of its bookings' squares,
// which bounds the se from above.
inline double exit_fraction_se_bound(const gonio::SimResult& r, size_t a, int c, int bookings) {
    const gonio::AngleResult& ar = r.angles[a];
    double s1 = 0.0, s2 = 0.0;
    for (size_t b = 0; b + 5 < ar.raw.size(); b += 6) {
        s1 += double(ar.raw[b + c]) / gonio::kFixedScale;
        s2 += double(ar.raw[b + 3 + c]) / gonio::kFixedScale;
    }
    const double N = double(ar.paths), m = s1 / N;
    return std::sqrt(std::max(0.0, double(bookings) * s2 / N - m * m) / N);
}

inline double exit_fraction_se(const gonio::SimResult& r, size_t a, int c) {
    return exit_fraction_se_bound(r, a, c, 1);   // one booking per path: the bound is the se
}

inline gonio::Layer dielectric(float ior, float roughness = 0.0f, glm::vec3 tau = glm::vec3(0.0f)) {
    gonio::Layer l;
    l.kind = gonio::InterfaceKind::Dielectric;
    l.ior = glm::vec3(ior);
    l.roughness = roughness;
    l.optical_depth = tau;
    return l;
}
inline gonio::Layer lambertian(glm::vec3 albedo) {
    gonio::Layer l;
    l.kind = gonio::InterfaceKind::Lambertian;
    l.albedo = albedo;
    return l;
}
inline gonio::Layer conductor(glm::vec3 ior, glm::vec3 k, float roughness = 0.0f) {
    gonio::Layer l;
    l.kind = gonio::InterfaceKind::Conductor;
    l.ior = ior;
    l.k = k;
    l.roughness = roughness;
    return l;
}
inline gonio::Stack make_stack(const std::string& name, std::vector<gonio::Layer> layers, float exterior = 1.0f) {
    gonio::Stack s;
    s.name = name;
    s.exterior_ior = exterior;
    s.layers = std::move(layers);
    gonio::validate_stack(s);
    return s;
}

}   // namespace gonio_test
