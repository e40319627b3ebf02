// compat.glsl: lets the physics files in shaders/lib compile both as GLSL (the device) and as C++ with GLM
// (the CPU twin used by the unit tests). Rules for shared files:
//   * float literals carry an `f` suffix; no swizzles beyond .x .y .z .w;
//   * out/inout parameters are written OUT(T) and INOUT(T);
//   * structs are filled field by field (no GLSL constructor syntax for structs).
#ifndef GONIO_COMPAT_GLSL
#define GONIO_COMPAT_GLSL

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/integer.hpp>
using glm::vec2; using glm::vec3; using glm::vec4; using glm::uvec2; using glm::uvec3; using glm::uvec4;
using glm::dot; using glm::cross; using glm::normalize; using glm::length; using glm::clamp; using glm::mix;
using glm::min; using glm::max; using glm::abs; using glm::exp; using glm::sqrt; using glm::inversesqrt;
using glm::floor; using glm::uintBitsToFloat; using glm::floatBitsToUint; using glm::findLSB;
using std::atan2; using std::acos; using std::cos; using std::sin; using std::log; using std::round; using std::pow;
using std::tan;
using std::int64_t; using std::uint64_t;
typedef uint32_t uint;
#define OUT(T) T&
#define INOUT(T) T&
#define GONIO_INLINE inline
#else
#define OUT(T) out T
#define INOUT(T) inout T
#define GONIO_INLINE
float atan2(float y, float x) { return atan(y, x); }
#endif

const float PI = 3.14159265358979f;
const float INV_PI = 0.318309886183791f;

#endif
