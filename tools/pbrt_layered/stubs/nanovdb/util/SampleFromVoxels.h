// STUB -- see ../NanoVDB.h. Not NanoVDB: only what pbrt-v4's media.h names.
#pragma once
#include <cstdlib>
#include "../NanoVDB.h"

namespace nanovdb {
template <typename TreeT, int Order, bool UseCache>
struct SampleFromVoxels {
    explicit SampleFromVoxels(const TreeT &) {}
    template <typename V>
    float operator()(const V &) const { std::abort(); }
};
}  // namespace nanovdb
