// one_row_ranges.h: compiled into every layerlab file (-include, CMakeLists.txt here), not part of gonio.
// layerlab's Layer::setHenyeyGreenstein (and setVonMisesFisher) append a thread's local list of Fourier entries to the
// shared one inside their loop over the range's rows and never clear it, so a range of k rows adds its first row k
// times, its second k - 1 times, ...: a medium that scatters is counted several times over, by an amount that depends
// on how TBB splits the rows (src/layer.cpp @3e5257e3, lines 131-151 and 166-190). Every tbb::parallel_for in layerlab
// takes a blocked_range of grainsize 1; under tbb::simple_partitioner each range its body receives is then one row,
// and the loop appends that row once. No layerlab file is modified; the arithmetic of every entry is layerlab's own.
#pragma once
#include <tbb/tbb.h>

namespace tbb {
template <typename Range, typename Body>
void layerlab_parallel_for_one_row(const Range& range, const Body& body) {
    tbb::parallel_for(range, body, tbb::simple_partitioner());
}
}   // namespace tbb

#define parallel_for layerlab_parallel_for_one_row
