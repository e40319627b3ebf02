// walk_runner.h: the one host of the walk kernels (simulate.comp, simulate_batch.comp) and fold.comp, which
// simulate_gpu, simulate_gpu_batch and ReferenceSession configure: the histograms of one or more configurations
// (device-local staging, totals and energy book, a mapped host copy), the stack's buffer, the fold, the timed
// dispatch-and-fold recording, and the checkpoints of --rse.
#pragma once
#include "angle_policy.h"
#include "compute_kernel.h"
#include "walk_kernel.h"
#include "kernel_interface.glsl"
#include "reference.h"
#include "vk_context.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>

namespace gonio {

// What every host of the walk kernels dispatches by: paths per workgroup and the most paths one dispatch may take.
struct WalkDispatch {
    uint64_t per_group;   // paths per workgroup: WALK_LOCAL_SIZE invocations of paths_per_invocation paths
    uint64_t max_paths;   // per dispatch: at most MAX_PATHS_PER_DISPATCH (bins.glsl: the packed halves must not
        // carry) and 65535 workgroups, in whole workgroups
    explicit WalkDispatch(uint32_t paths_per_invocation)
        : per_group(uint64_t(WALK_LOCAL_SIZE) * paths_per_invocation),
          max_paths(std::min<uint64_t>(65535ull, MAX_PATHS_PER_DISPATCH / per_group) * per_group) {}
    uint32_t groups(uint64_t paths) const { return uint32_t((paths + per_group - 1) / per_group); }
};

// The push constants of one incident angle of a run (stream: the angle's index); the hosts set path_base_* and
// path_count per dispatch, simulate_batch.comp's host staging_stride.
WalkPush walk_push(const WalkGrid& g, double dtheta_deg, double dphi_deg, uint32_t max_events, double theta_i_deg,
                   double phi_i_deg, uint32_t seed, uint32_t stream);

// simulate.comp's entry for one incident angle: pc's paths (path_base_*, path_count), seed mix and direction, booked
// into the histograms of `slot`.
inline WalkAngle walk_angle(const WalkPush& pc, uint32_t slot) {
    return WalkAngle{pc.path_base_lo, pc.path_base_hi, pc.path_count, slot,      pc.seed_mix0,
                     pc.seed_mix1,    pc.sin_ti,       pc.cos_ti,     pc.sin_pi, pc.cos_pi};
}

// Throws std::invalid_argument, saying how large the grid is and what the device allows, if the histograms of a run
// (bins x sides x path classes) do not fit the device's buffers or memory.
void check_histograms_fit(VkContext& ctx, uint64_t histogram_bytes, const std::string& what);
// How many configurations of `values` raw totals each fit at once: check_histograms_fit's limits and one fold
// dispatch (fold_workgroups); 0 if not even one does (check_histograms_fit then says why).
size_t configurations_that_fit(VkContext& ctx, size_t values);

class WalkRunner {
public:
    // The histograms of `configs` configurations of `values` raw totals each (what: the run, for check_histograms_fit's
    // message), the stack's buffer: a uniform block (simulate.comp) or a storage buffer (simulate_batch.comp's
    // stacks) of stack_bytes, mapped, and simulate.comp's table of `configs` incident angles (WalkAngle), mapped.
    WalkRunner(VkContext& ctx, size_t values, size_t configs, vk::DescriptorType stack_type, vk::DeviceSize stack_bytes,
               const std::string& what);
    WalkRunner(const WalkRunner&) = delete;
    WalkRunner& operator=(const WalkRunner&) = delete;

    void* stack_mapped() { return stack_.mapped; }
    // simulate.comp's angles: entry y is what workgroup row y of the next dispatch traces (written before submitting)
    WalkAngle* angles_mapped() { return static_cast<WalkAngle*>(angles_.mapped); }
    // A walk kernel bound to (stack, staging, energy); build_walk_kernel builds its pipeline.
    std::unique_ptr<ComputeKernel> make_kernel(const uint32_t* spv, size_t bytes);

    // Transfers, waiting for them: zero every histogram and the host copy; the host copy into the totals and the
    // energy book (--resume); those back into the host copy.
    void clear();
    void upload();
    void read_back();
    uint64_t* host_totals(size_t config = 0) { return host_totals_ + config * values_; }
    int64_t* host_energy(size_t config = 0) { return host_energy_ + config * ENERGY_ENTRIES; }
    // The host copy of one configuration (its first `values` totals, all by default) as an angle of `paths` paths.
    AngleResult angle(size_t config, uint64_t paths, size_t values = 0) const;

    // One dispatch of `groups` x `configs` workgroups of k and the fold of every configuration's staging (weights
    // scaled by 2^-shift) after it (fold_after) and/or before it (fold_before: the staging may hold at most
    // MAX_PATHS_PER_DISPATCH paths per configuration between folds), timed; waits. Returns the device seconds.
    double run(const ComputeKernel& k, const WalkPush& pc, uint32_t groups, uint32_t configs, uint32_t shift,
               bool fold_after = true, bool fold_before = false);
    // The fold alone, waiting for it: the staging's paths into the totals before they are read back.
    void fold_now(uint32_t shift);

    // The pieces of run, for hosts that submit without waiting (ReferenceSession): record into begin()'s command
    // buffer, then submit(); done() polls, wait() blocks, timer_seconds() reads the timestamps once done.
    vk::CommandBuffer begin();
    void record_start_timer(vk::CommandBuffer c);
    void record_walk(vk::CommandBuffer c, const ComputeKernel& k, const WalkPush& pc, uint32_t groups,
                     uint32_t configs);
    void record_fold(vk::CommandBuffer c, uint64_t staging_values, uint32_t shift);   // after a barrier from the walk
    void record_barrier(vk::CommandBuffer c);   // compute -> compute
    void record_copy_to_host(vk::CommandBuffer c, size_t values);   // totals[0, values) and the energy book
    void record_stop_timer(vk::CommandBuffer c);
    void submit();
    bool done();
    void wait();
    double timer_seconds();

    size_t values() const { return values_; }
    size_t configurations() const { return configs_; }   // of histograms held (angle slots, stacks)

private:
    VkContext& ctx_;
    size_t values_, configs_;
    Buffer stack_, staging_, totals_, energy_, host_, angles_;
    vk::DescriptorType stack_type_;
    uint64_t* host_totals_;
    int64_t* host_energy_;
    std::unique_ptr<ComputeKernel> fold_;
    vk::raii::QueryPool queries_ = nullptr;
    vk::raii::CommandBuffer cb_ = nullptr;
    vk::raii::Fence fence_ = nullptr;
    void transfer(bool upload);
};

}   // namespace gonio
