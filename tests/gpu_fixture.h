// gpu_fixture.h: one Vulkan context per test binary, with the Khronos validation layer on; any validation
// message fails the test that produced it.
#pragma once
#include "histogram.h"
#include "reference.h"
#include "stack.h"
#include "vk_context.h"

#include <gtest/gtest.h>

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

}  // namespace gonio_test
