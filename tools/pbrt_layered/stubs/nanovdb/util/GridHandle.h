// STUB -- see ../NanoVDB.h. Not NanoVDB: only what pbrt-v4's media.h names.
#pragma once
#include "../NanoVDB.h"

namespace nanovdb {
template <typename BufferT>
class GridHandle {
  public:
    GridHandle() = default;
};
}  // namespace nanovdb
