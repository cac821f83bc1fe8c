// The random numbers of SNEE's two subdivision strategies, by name: each strategy takes one
// array u per exit, and these are the positions in it. The scalar samplers
// (snee_strategies.cpp), their batched parts (kernels/simd/) and the subdivision stage, which
// draws the arrays, all index by these names.
#pragma once

#include "kernels/physics/snee/joint_importance.h"

namespace snee {

struct TopToBottomRandoms {
  static constexpr int kLightSelection = 0;
  static constexpr int kLightPoint = 1;    // two numbers: the point on the light
  static constexpr int kInwardNormal = 3;  // two: microfacet normal of the inward transmission
  static constexpr int kDistanceTechnique = 5;
  static constexpr int kDistanceChannel = 6;  // free-flight colour channel
  static constexpr int kDistance = 7;
  static constexpr int kCount = 8;
};
inline constexpr int kTopToBottomDimensions = TopToBottomRandoms::kCount;

struct BottomToTopRandoms {
  static constexpr int kPlacement = 0;  // joint_importance_sample's numbers
  static constexpr int kOutwardNormal = kPlacement + kJointImportanceDimensions;  // two
  static constexpr int kCount = kOutwardNormal + 2;
};
inline constexpr int kBottomToTopDimensions = BottomToTopRandoms::kCount;

}  // namespace snee
