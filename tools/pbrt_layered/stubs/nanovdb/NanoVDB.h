// STUB -- written for gonio's tools/pbrt_layered harness; NOT NanoVDB.
//
// pbrt-v4's media.h (pulled in by bxdfs.h) includes NanoVDB headers for its NanoVDBMedium, which the
// harness never uses. NanoVDB lives in pbrt's ext/openvdb submodule, which a bare checkout lacks.
// These declarations are just enough for media.h's inline NanoVDBMedium methods to compile; nothing
// here is ever called (calling it aborts). Do not use them for anything else.
#pragma once
#include <cstdlib>

namespace nanovdb {

template <typename T>
struct Vec3 {
    T x, y, z;
    Vec3() = default;
    Vec3(T x, T y, T z) : x(x), y(y), z(z) {}
};

struct FloatTreeStub {};

struct FloatGrid {
    using TreeType = FloatTreeStub;
    template <typename V>
    V worldToIndexF(const V &) const { std::abort(); }
    const TreeType &tree() const { std::abort(); }
};

}  // namespace nanovdb
