// Helpers for tests that render whole images: small scenes built in code, and statistics over
// image regions using the film's per-pixel variance of the mean.
#pragma once

#include <vector>

#include "scene/film.h"
#include "scene/scene.h"

namespace snee::test {

// Same size and the same bits in every mean and variance value.
bool bitwise_identical(const Film& a, const Film& b);

// A unit sphere at the origin filled with `medium`, bounded by `material`, seen by a camera
// that frames it, with no lights (add them).
Scene sphere_scene(const Material& material, const Medium& medium, int resolution);

struct RegionStats {
  double mean = 0;
  double standard_error = 0;
  int pixels = 0;
};

// Mean of channel-averaged pixel values over the pixels where mask is true, with the standard
// error of that mean from the per-pixel variances (pixels are independent).
RegionStats region_mean(const Film& film, const std::vector<bool>& mask);
// The pixels whose camera ray hits the sphere (by default the unit sphere at the origin) in
// their whole footprint: all four corners inside the silhouette. For a pinhole camera with a
// vertical fov.
std::vector<bool> sphere_mask(const Scene& scene, Vec3 center = {0, 0, 0}, float radius = 1);
// Expects the whole image and each of its 8x8 blocks to average to 1 within their standard
// errors (4 and 5 SE), as a white furnace must.
void expect_renders_to_one(const Film& film);
// Square blocks of `block` pixels intersected with a mask (blocks with fewer than min_pixels
// masked pixels are dropped).
std::vector<std::vector<bool>> blocks(const Film& film, const std::vector<bool>& mask, int block,
                                      int min_pixels);

}  // namespace snee::test
