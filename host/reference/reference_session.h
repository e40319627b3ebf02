// reference_session.h: the reference, progressively: one stack and one incident angle, accumulated in small
// slices of paths that are submitted without waiting (the viewer submits one per frame). The pipelines stay
// alive between restarts, so a new stack or angle costs no new JIT compile on lavapipe (the general walk by
// default: its specialisation does not depend on the stack's parameters).
//
// The sums are those simulate_gpu computes: after N paths the raw totals are byte-identical to
// simulate_gpu(stack, {theta_i} at phi_i, N paths, same seed, same walk), whatever the slices were
// (tests/test_reference_session.cpp).
#pragma once
#include "reference.h"

#include <cstdint>
#include <memory>

namespace gonio {

struct SessionOptions {
    uint32_t seed = 1;
    double dtheta_deg = 1.0;
    double dphi_deg = 2.0;
    uint32_t max_events = 256;
    uint32_t paths_per_invocation = 16;
    bool specialised = false;   // true: specialise on the stack's shape (a new pipeline, JIT, per shape)
};

class ReferenceSession {
public:
    ReferenceSession(VkContext& ctx, const SessionOptions& opt);
    ~ReferenceSession();
    ReferenceSession(const ReferenceSession&) = delete;
    ReferenceSession& operator=(const ReferenceSession&) = delete;

    // Start over with this stack and incident direction (waits for the slice in flight, clears the sums): polar angle
    // theta_i in [0, 90) and azimuth phi_i in [0, 360) degrees. Throws StackError / std::invalid_argument for a stack
    // or angle that cannot run.
    void restart(const Stack& stack, double theta_i_deg, double phi_i_deg = 0.0);

    // Submits the next `paths` paths (rounded up to whole workgroups, capped to one dispatch) without
    // waiting. Returns false (and does nothing) while a slice is still in flight. With readback, the slice
    // also folds the staging histogram into the totals and copies them for result(); without, the paths stay
    // in the staging histogram (folded when it could overflow) and result() still shows the earlier sums:
    // a slice then costs only its paths, not a pass over every bin.
    bool submit(uint64_t paths, bool readback = true);
    // Non-blocking: true when no slice is in flight. A finished slice is collected: its paths count from now on.
    bool poll();
    // Waits for the slice in flight, if any, and collects it.
    void wait();

    uint64_t paths() const;   // paths traced so far (collected slices)
    uint64_t readable_paths() const;   // paths in the sums result() returns (the last readback)
    double last_slice_device_seconds() const;
    uint64_t last_slice_paths() const;
    double device_seconds() const;   // since the last restart
    bool busy() const;

    // The collected sums as a one-angle result (make_slice, energy_book and worst_relative_se take it).
    // Copies the sums out of the readback buffer; only valid when !busy() (call poll() first).
    const SimResult& result();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}   // namespace gonio
