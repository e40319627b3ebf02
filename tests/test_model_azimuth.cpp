// The models' bins at an incident azimuth phi_i (ModelGrid::phi_i_deg; shaders/models.comp to_surface_frame).
//
// The bins stay in the surface's frame; light arrives from l = (sin theta_i cos phi_i, sin theta_i sin phi_i,
// cos theta_i). Every model gonio evaluates is isotropic (f depends on the azimuth of v relative to l's), so:
//   * a quarter turn (phi_i 90 on 10-degree bins: 9 whole bins) gives the plane's bins turned, bin j at phi_i 90 the
//     bin j - 9 at phi_i 0, up to the float rounding of turning l and v (the device turns them before the model sees
//     them) and of the lobe grids' nodes; every built-in model that represents the stack, a user's model with
//     announced lobes, and the delta lobes of smooth coats (booked whole in the mirror direction's bin, which moves
//     with l; at normal incidence it is the pole, which the bins book at phi = 0 (bins.glsl bin_index) at any
//     azimuth: there the first ring is compared as a whole);
//   * an azimuth between bin centres (phi_i 37.5 on 10-degree bins: its bins' edges at relative azimuths
//     10 j - 42.5) gives the mean of the ten 1-degree bins of phi_i 0 that tile each bin, within the two
//     quadratures' own errors (measured 3e-5 of the value); a bin moved the wrong way by the rest of phi_i (a
//     2.5-degree error) is off by up to a third next to the lobes' peak.
#include "gpu_fixture.h"
#include "model_evaluator.h"
#include "text_format.h"
#include "user_model.h"

#include <algorithm>
#include <cmath>
#include <string>

using namespace gonio;
using namespace gonio_test;

namespace {

class ModelAzimuth : public GpuTest {};

const std::string kUserModel = std::string(GONIO_SOURCE_DIR) + "/tests/user_models/ww_corrected_delta.glsl";

ModelGrid grid(double dphi, double phi_i) {
    return {18, uint32_t(std::lround(360.0 / dphi)), 5.0, dphi, {0.0, 30.0, 70.0}, phi_i};
}

std::vector<ModelSlices> evaluate(ModelEvaluator& ev, const Stack& s, const ModelGrid& g, bool user) {
    ModelOptions o;
    if (user) o.user_models.push_back(load_user_model(kUserModel));
    return ev.evaluate(s, g, nullptr, o);
}

bool has_bins(const ModelSlices& m) { return m.not_applicable.empty() && !m.f.empty(); }

double peak(const std::vector<glm::dvec3>& f) {
    double p = 0.0;
    for (const auto& v : f) p = std::max({p, v.x, v.y, v.z});
    return p;
}

// The stacks: a rough absorbing coat over a Lambertian (most models represent it), a smooth coat over a Lambertian
// (delta lobes, the user's model's announced delta), a smooth coat over copper and a rough slab (transmission side)
std::vector<Stack> stacks() {
    return {
        make_stack("rough-coat", {dielectric(1.5f, 0.1f, glm::vec3(0.05f, 0.1f, 0.2f)), lambertian(glm::vec3(0.6f))}),
        make_stack("smooth-coat", {dielectric(1.5f, 0.0f), lambertian(glm::vec3(0.5f, 0.3f, 0.2f))}),
        make_stack("smooth-coat-copper",
                   {dielectric(1.5f, 0.0f, glm::vec3(0.1f)),
                    conductor(glm::vec3(0.27f, 0.68f, 1.22f), glm::vec3(3.6f, 2.6f, 2.3f), 0.2f)}),
        make_stack("rough-slab", {dielectric(1.5f, 0.2f)})};
}

TEST_F(ModelAzimuth, AQuarterTurnTurnsEveryModelsBins) {
    ModelEvaluator ev(context());
    const ModelGrid g0 = grid(10.0, 0.0), g90 = grid(10.0, 90.0);
    const uint32_t shift = 9, n_phi = g0.n_phi;
    size_t slices = 0, users = 0;
    for (const Stack& s : stacks()) {
        const bool user = s.name == "rough-coat" || s.name == "smooth-coat";
        const std::vector<ModelSlices> a = evaluate(ev, s, g0, user), b = evaluate(ev, s, g90, user);
        ASSERT_EQ(a.size(), b.size());
        for (size_t m = 0; m < a.size(); ++m) {
            if (!has_bins(a[m])) continue;
            ASSERT_TRUE(has_bins(b[m])) << s.name << " " << b[m].id << ": " << b[m].not_applicable << b[m].invalid;
            users += a[m].id == "ww-corrected-delta";
            for (int side = 0; side < (a[m].t.empty() ? 1 : 2); ++side)
                for (size_t ai = 0; ai < g0.theta_i_deg.size(); ++ai) {
                    const auto& f0 = (side ? a[m].t : a[m].f)[ai];
                    const auto& f90 = (side ? b[m].t : b[m].f)[ai];
                    const double floor = 1e-7 * peak(f0) + 1e-9;
                    ++slices;
                    const bool pole = g0.theta_i_deg[ai] == 0.0;
                    if (pole) {   // the first ring's sums (the pole's delta in bin (0, 0) at any azimuth)
                        glm::dvec3 r0(0.0), r90(0.0);
                        for (uint32_t j = 0; j < n_phi; ++j) r0 += f0[j], r90 += f90[j];
                        for (int c = 0; c < 3; ++c)
                            ASSERT_LE(std::fabs(r90[c] - r0[c]), 1e-5 * std::fabs(r0[c]) + floor)
                                << s.name << " " << a[m].id << " theta_i 0: the first ring's sum, channel " << c;
                    }
                    for (uint32_t t = pole ? 1 : 0; t < g0.n_theta; ++t)
                        for (uint32_t j = 0; j < n_phi; ++j) {
                            const glm::dvec3 want = f0[t * n_phi + (j + n_phi - shift) % n_phi];
                            const glm::dvec3 got = f90[t * n_phi + j];
                            for (int c = 0; c < 3; ++c)
                                ASSERT_LE(std::fabs(got[c] - want[c]), 1e-5 * std::fabs(want[c]) + floor)
                                    << s.name << " " << a[m].id << (side ? " T" : " R") << " theta_i "
                                    << g0.theta_i_deg[ai] << " bin (" << t << ", " << j << ") channel " << c;
                        }
                }
        }
    }
    EXPECT_EQ(users, 2u);   // the user's model on both coats
    EXPECT_GE(slices, 60u);
}

TEST_F(ModelAzimuth, AnAzimuthBetweenBinCentresIsTheFinePlanesBins) {
    ModelEvaluator ev(context());
    const ModelGrid coarse = grid(10.0, 37.5), fine = grid(1.0, 0.0);
    const Stack s = stacks()[0];
    const std::vector<ModelSlices> a = evaluate(ev, s, coarse, false), b = evaluate(ev, s, fine, false);
    size_t slices = 0;
    for (size_t m = 0; m < a.size(); ++m) {
        if (!has_bins(a[m])) continue;
        ASSERT_TRUE(has_bins(b[m])) << b[m].id;
        for (size_t ai = 0; ai < coarse.theta_i_deg.size(); ++ai) {
            const auto& fc = a[m].f[ai];
            const auto& ff = b[m].f[ai];
            const double floor = 1e-5 * peak(ff) + 1e-9;
            ++slices;
            for (uint32_t t = 0; t < coarse.n_theta; ++t)
                for (uint32_t j = 0; j < coarse.n_phi; ++j) {
                    // bin j: relative azimuths [10 j - 42.5, 10 j - 32.5], the fine bins centred on 10 j - 42 ... - 33
                    glm::dvec3 want(0.0);
                    for (int k = 0; k < 10; ++k)
                        want += ff[t * fine.n_phi + uint32_t((int(10 * j) - 42 + k + 720) % 360)] / 10.0;
                    const glm::dvec3 got = fc[t * coarse.n_phi + j];
                    for (int c = 0; c < 3; ++c)
                        ASSERT_LE(std::fabs(got[c] - want[c]), 2e-4 * std::fabs(want[c]) + floor)
                            << a[m].id << " theta_i " << coarse.theta_i_deg[ai] << " bin (" << t << ", " << j
                            << ") channel " << c;
                }
        }
    }
    EXPECT_GE(slices, 15u);   // the coat models at three angles
}

}   // namespace
