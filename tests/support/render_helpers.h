// Helpers for tests that render whole images: small scenes built in code, and statistics over
// image regions using the film's per-pixel variance of the mean.
#pragma once

#include <string>
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
// Two renders of one scene agree over `mask`: as a whole within 4 combined standard errors, and
// in every block (blocks(film, mask, block, min_pixels)) within 5 (a Bonferroni-safe bound for
// some 16 blocks) where both have converged there. A block counts as converged when its relative
// standard error is below 10% in both: dim regions lit only through rare paths (the shadowed
// side, for an estimator that finds a small light by chance) have heavy-tailed estimates whose
// sample variance under-reports their error, and a z-test there would measure the sample count,
// not bias. Returns the number of blocks compared.
int expect_same_region(const Film& a, const Film& b, const std::vector<bool>& mask, int block,
                       int min_pixels, const std::string& what);
// expect_same_region over the whole image, in blocks of a quarter of its width.
int expect_same_image(const Film& a, const Film& b, const std::string& what);
// Adds a 2 x 2 square emitter at height 3 above the unit sphere, emitting downward, as an area
// light.
void add_panel_emitter(Scene& scene, Rgb emission);
// Replaces the lights by that panel (emission 1.5) and a point light of intensity 6 at
// (2.5, 0.5, 1.5): an area light and a finite delta light over the unit sphere.
void light_by_panel_and_bulb(Scene& scene);
// Square blocks of `block` pixels intersected with a mask (blocks with fewer than min_pixels
// masked pixels are dropped).
std::vector<std::vector<bool>> blocks(const Film& film, const std::vector<bool>& mask, int block,
                                      int min_pixels);

}  // namespace snee::test
