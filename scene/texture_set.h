// The scene's textures behind OpenImageIO's TextureSystem: MIP-mapped (the levels are made when
// a texture is first looked up), cached in tiles, safe to look up from any number of threads.
// The pixels come from the scene's decoded images in memory (Scene::textures, linear RGB), never
// from files, so a render reads no file after loading and filters linear values, not sRGB
// codes. Lookups wrap as each texture says (Texture) and filter bilinearly between the two MIP
// levels nearest the footprint (OpenImageIO's trilinear mode).
#pragma once

#include <memory>
#include <vector>

#include "core/math.h"
#include "scene/scene.h"

namespace snee {

class TextureSet {
 public:
  // `textures` must outlive the set: its pixels are read from there, as tiles are needed.
  // Throws SceneError naming the image if the texture system cannot use one of them.
  explicit TextureSet(const std::vector<Texture>& textures);
  ~TextureSet();
  TextureSet(const TextureSet&) = delete;
  TextureSet& operator=(const TextureSet&) = delete;

  // Texture `texture` at uv, filtered over a square footprint `width` texture units on a side
  // (0: the finest level, bilinearly).
  Rgb lookup(int texture, Uv uv, float width) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace snee
