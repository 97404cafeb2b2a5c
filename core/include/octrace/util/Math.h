#pragma once
/// @file Math.h
/// The math types of octrace, in one place (GLM with GLSL names).
#include <glm/glm.hpp>
#include <cstdint>

namespace octrace {
using dvec2 = glm::dvec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using dvec3 = glm::dvec3;
using dvec4 = glm::dvec4;
using ivec3 = glm::ivec3;
using i64vec3 = glm::i64vec3;
using dmat3 = glm::dmat3;
using mat3 = glm::mat3;

/// Axis-aligned box in world space [lo, hi].
struct Box3 {
    dvec3 lo{0.0};
    dvec3 hi{0.0};
    dvec3 size() const { return hi - lo; }
    dvec3 centre() const { return 0.5 * (lo + hi); }
};
}  // namespace octrace
