// The viewer's progressive reference (host/reference/reference_session.h): slices submitted one at a time add up to
// the same bytes as one simulate_gpu run, through restarts with other stacks and angles, validation silent.
#include "gpu_fixture.h"
#include "reference_session.h"

#include <cstring>

using namespace gonio;
using namespace gonio_test;

namespace {

class Session : public GpuTest {};

void expect_same(const SimResult& one_run, const SimResult& progressive, const std::string& what) {
    ASSERT_EQ(one_run.angles.size(), 1u);
    const AngleResult& a = one_run.angles[0];
    const AngleResult& b = progressive.angles.at(0);
    EXPECT_EQ(a.paths, b.paths) << what;
    ASSERT_EQ(a.raw.size(), b.raw.size()) << what;
    EXPECT_TRUE(a.raw == b.raw) << what << ": histogram differs";
    EXPECT_EQ(std::memcmp(a.energy, b.energy, sizeof(a.energy)), 0) << what << ": energy book differs";
}

// Run slices of uneven sizes, most without readback (paths stay in the staging histogram, which must be
// folded before it could overflow), until at least `paths` paths; the last one reads back.
uint64_t run_slices(ReferenceSession& s, uint64_t paths) {
    const uint64_t sizes[] = {1024, 5000, 700000, 3000, 400000};
    for (int i = 0; s.paths() < paths; ++i) {
        uint64_t n = std::min<uint64_t>(sizes[i % 5], paths - s.paths());
        bool last = s.paths() + n >= paths;
        EXPECT_TRUE(s.submit(n, last || i % 3 == 2));
        EXPECT_FALSE(s.submit(n)) << "a second slice while one is in flight";
        while (!s.poll()) {}
    }
    EXPECT_EQ(s.readable_paths(), s.paths());
    return s.paths();
}

TEST_F(Session, SlicesAddUpToOneRun) {
    Stack plastic = parse_stack_file(std::string(GONIO_SOURCE_DIR) + "/stacks/plastic.toml");
    Stack frosted = parse_stack_file(std::string(GONIO_SOURCE_DIR) + "/stacks/frosted-metal.toml");
    SessionOptions so;
    so.seed = 7;
    ReferenceSession session(context(), so);
    // (stack, theta_i, phi_i): an incident azimuth too, the session's own pipeline for it
    struct Case {
        const Stack* stack;
        double ti, pi;
    };
    for (auto [stack, ti, pi] : {Case{&frosted, 30.0, 0.0}, Case{&plastic, 60.0, 0.0}, Case{&frosted, 0.0, 0.0},
                                 Case{&frosted, 40.0, 135.0}}) {
        session.restart(*stack, ti, pi);
        uint64_t n = run_slices(session, 2500000);
        SimOptions o;
        o.theta_i_deg = {ti};
        o.phi_i_deg = pi;
        o.paths = n;
        o.seed = so.seed;
        o.specialised = false;
        SimResult one = simulate_gpu(context(), *stack, o);
        const SimResult& prog = session.result();
        expect_same(one, prog, stack->name + " at " + std::to_string(ti) + ", phi_i " + std::to_string(pi));
        EXPECT_EQ(prog.angles[0].phi_i_deg, pi);
        double med = median_relative_se(prog, prog.angles[0], kReflection);
        EXPECT_GT(med, 0.0);
        EXPECT_LT(med, 1.0);
    }
}

TEST_F(Session, RefusesBadInput) {
    ReferenceSession session(context(), SessionOptions{});
    Stack plastic = parse_stack_file(std::string(GONIO_SOURCE_DIR) + "/stacks/plastic.toml");
    EXPECT_THROW(session.restart(plastic, 90.0), std::invalid_argument);
    EXPECT_THROW(session.restart(plastic, 30.0, 360.0), std::invalid_argument);
    EXPECT_THROW(session.restart(plastic, 30.0, -1.0), std::invalid_argument);
    EXPECT_THROW(session.submit(1000), std::logic_error);
    Stack bad = plastic;
    bad.layers[0].roughness = -1.0f;
    EXPECT_THROW(session.restart(bad, 10.0), StackError);
}

}   // namespace
