// walk_dispatch.h: what every host of the walk kernels (simulate.comp, simulate_batch.comp) dispatches by: paths
// per workgroup, the most paths one dispatch may take, and the rounds of --rse.
#pragma once
#include "stack_gpu.h"   // bins.glsl through the CPU twin: WALK_LOCAL_SIZE, MAX_PATHS_PER_DISPATCH

#include <algorithm>
#include <cstdint>

namespace gonio {

struct WalkDispatch {
    uint64_t per_group;   // paths per workgroup: WALK_LOCAL_SIZE invocations of paths_per_invocation paths
    uint64_t max_paths;   // per dispatch: at most MAX_PATHS_PER_DISPATCH (bins.glsl: the packed halves must not
                          // carry) and 65535 workgroups, in whole workgroups
    explicit WalkDispatch(uint32_t paths_per_invocation)
        : per_group(uint64_t(WALK_LOCAL_SIZE) * paths_per_invocation),
          max_paths(std::min<uint64_t>(65535ull, MAX_PATHS_PER_DISPATCH / per_group) * per_group) {}
    uint32_t groups(uint64_t paths) const { return uint32_t((paths + per_group - 1) / per_group); }
};

// --rse: the paths grow in rounds that end at 2^20 x 2^k paths (capped by `cap`), where the target is checked, so
// the stopping point does not depend on the dispatch sizes: the end of the round after `from` paths.
inline uint64_t rse_round_end(uint64_t from, uint64_t cap) {
    uint64_t c = 1u << 20;
    while (c <= from) c *= 2;
    return std::min(c, cap);
}

}  // namespace gonio
