// Two scenes compared field by field, and the canonical round trip of a loaded scene: what the
// scene format's tests (test_scene_loader.cpp, test_scene_errors.cpp, test_builtin_scenes.cpp)
// check a reload with.
#pragma once

#include <string>

#include "scene/scene_loader.h"

namespace snee::test {

void expect_same_transform(const Transform& a, const Transform& b);
void expect_same_scene(const Scene& a, const Scene& b);
// Loads the canonical document again (from another directory, so relative paths would break)
// and expects the same scene and the same canonical document.
void expect_round_trip(const LoadedScene& first, const std::string& origin);
// The largest distance of a vertex from `center`.
double bounding_radius(const TriangleMesh& mesh, Vec3 center);

}  // namespace snee::test
