// Textures (scene/texture_set.h and the loader's "albedo_texture"): lookups filter linear
// values as OpenImageIO's TextureSystem does, wrap as asked and average over wide footprints;
// bad textures and surfaces without texture coordinates are clear errors naming the JSON path.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include <string>

#include "scene/rgb_image_io.h"
#include "scene/scene_loader.h"
#include "scene/surface_uv.h"
#include "scene/texture_set.h"
#include "tests/support/scene_error_of.h"
#include "tests/support/test_directory.h"
#include "tests/support/texture_images.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quadrant_colour;

void expect_rgb(Rgb got, Rgb expected, float tolerance, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], tolerance) << what << " ch " << c;
}

class TextureTest : public test::QuadrantTextureTest {
 protected:
  TextureTest() : QuadrantTextureTest("test_textures") {}

  // The set reads its pixels from these as it needs them, so they outlive it.
  std::vector<Texture> quadrant_textures() const {
    return load_scene_json(textured_quad_scene(), "textures", dir_.string()).scene.textures;
  }

  // A textured quad seen from above under a light from above.
  static json textured_quad_scene(const json& material = {{"type", "diffuse"},
                                                          {"albedo_texture", "quadrants.exr"}}) {
    return {{"camera",
             {{"position", {0.0, 2.0, 0.0}},
              {"look_at", {0.0, 0.0, 0.0}},
              {"up", {0.0, 0.0, -1.0}},
              {"resolution", {8, 8}}}},
            {"shapes", {{{"type", "quad"}, {"size", 2.0}, {"material", material}}}},
            {"lights", {{{"type", "directional"}, {"direction", {0.0, 1.0, 0.0}}}}}};
  }
};

// Between the texel centres of a quadrant the bilinear lookup is that quadrant's colour; half
// way between the centres of two texels of different quadrants it is their mean.
TEST_F(TextureTest, PointLookupsAreBilinearInLinearValues) {
  const std::vector<Texture> textures = quadrant_textures();
  const TextureSet set(textures);
  const float plateau[2] = {1.0f / 8, 3.0f / 8};  // within texel centres 0.5/8 .. 3.5/8
  for (int q = 0; q < 4; ++q) {
    for (const float a : plateau) {
      for (const float b : plateau) {
        const Uv uv{a + 0.5f * (q % 2), b + 0.5f * (q / 2)};
        expect_rgb(set.lookup(0, uv, 0.0f), quadrant_colour(q), 1e-6f,
                   "quadrant " + std::to_string(q));
      }
    }
  }
  expect_rgb(set.lookup(0, {0.5f, 0.25f}, 0.0f), (quadrant_colour(0) + quadrant_colour(1)) * 0.5f,
             1e-6f, "the A|B edge");
}

// Repeat (the default and the loader's), mirror and clamp, as glTF's samplers name them.
TEST_F(TextureTest, WrapModesRepeatMirrorAndClamp) {
  std::vector<Texture> textures = quadrant_textures();
  textures.push_back(textures[0]);
  textures.push_back(textures[0]);
  textures[1].wrap_u = textures[1].wrap_v = TextureWrap::kMirror;
  textures[2].wrap_u = textures[2].wrap_v = TextureWrap::kClamp;
  const TextureSet set(textures);
  // u = 1.3 repeats to 0.3 (top-left), clamps to the last column (top-right); u = -0.2 mirrors
  // to 0.2 (top-left) and repeats to 0.8 (top-right).
  expect_rgb(set.lookup(0, {1.3f, 0.25f}, 0.0f), quadrant_colour(0), 1e-6f, "repeat 1.3");
  expect_rgb(set.lookup(2, {1.3f, 0.25f}, 0.0f), quadrant_colour(1), 1e-6f, "clamp 1.3");
  expect_rgb(set.lookup(1, {-0.2f, 0.25f}, 0.0f), quadrant_colour(0), 1e-6f, "mirror -0.2");
  expect_rgb(set.lookup(0, {-0.2f, 0.25f}, 0.0f), quadrant_colour(1), 1e-6f, "repeat -0.2");
  // v = 1.8 mirrors to 0.2 (top) and repeats to 0.8 (bottom).
  expect_rgb(set.lookup(1, {0.25f, 1.8f}, 0.0f), quadrant_colour(0), 1e-6f, "mirror v 1.8");
  expect_rgb(set.lookup(0, {0.25f, 1.8f}, 0.0f), quadrant_colour(2), 1e-6f, "repeat v 1.8");
}

// A footprint as wide as the texture reads the coarsest MIP level, the mean of the image: the
// pyramid averages linear values, so filtering keeps the texture's mean reflectance.
TEST_F(TextureTest, WideFootprintsAverageTheImage) {
  const std::vector<Texture> textures = quadrant_textures();
  const TextureSet set(textures);
  const Rgb mean =
      (quadrant_colour(0) + quadrant_colour(1) + quadrant_colour(2) + quadrant_colour(3)) * 0.25f;
  for (const Uv uv : {Uv{0.1f, 0.1f}, Uv{0.6f, 0.3f}, Uv{0.9f, 0.9f}}) {
    expect_rgb(set.lookup(0, uv, 2.0f), mean, 1e-5f, "1x1 level");
  }
  // A footprint of two texels blends the finest two levels; inside a quadrant's plateau of the
  // 4x4 level (its texel centres at 1/8 and 3/8) the colour is still the quadrant's.
  expect_rgb(set.lookup(0, {0.25f, 0.25f}, 2.0f / 8), quadrant_colour(0), 1e-6f, "two texels");
}

TEST_F(TextureTest, LoaderReadsATextureOncePerFileWithAWhiteFactor) {
  json doc = textured_quad_scene();
  doc["materials"] = {{{"name", "tinted"},
                       {"type", "diffuse"},
                       {"albedo", {0.5, 0.5, 0.5}},
                       {"albedo_texture", "quadrants.exr"}}};
  doc["shapes"].push_back({{"type", "quad"}, {"size", 1.0}, {"material", "tinted"}});
  const Scene scene = load_scene_json(doc, "textures", dir_.string()).scene;
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].image.width, 8);
  ASSERT_EQ(scene.materials.size(), 2u);
  for (const Material& m : scene.materials) EXPECT_EQ(m.albedo_texture, 0);
  expect_rgb(scene.materials[0].albedo, Rgb(0.5f), 0, "named");
  expect_rgb(scene.materials[1].albedo, Rgb(1.0f), 0, "inline, no factor");
  ASSERT_EQ(scene.shapes[1].mesh.uvs.size(), 4u);
}

TEST_F(TextureTest, BadTexturesNameTheFileAndTheJsonPath) {
  const std::string missing = test::scene_error_of([&] {
    load_scene_json(textured_quad_scene({{"type", "diffuse"}, {"albedo_texture", "nope.png"}}),
                    "scene.json", dir_.string());
  });
  EXPECT_NE(missing.find("shapes[0].material.albedo_texture"), std::string::npos) << missing;
  EXPECT_NE(missing.find("nope.png"), std::string::npos) << missing;

  std::ofstream(dir_ / "text.png") << "not an image";
  const std::string broken = test::scene_error_of([&] {
    load_scene_json(textured_quad_scene({{"type", "diffuse"}, {"albedo_texture", "text.png"}}),
                    "scene.json", dir_.string());
  });
  EXPECT_NE(broken.find("text.png: cannot read texture"), std::string::npos) << broken;

  std::ofstream(dir_ / "bare.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  json bare = textured_quad_scene();
  bare["shapes"][0] = {{"type", "mesh"},
                       {"file", "bare.obj"},
                       {"material", {{"type", "diffuse"}, {"albedo_texture", "quadrants.exr"}}}};
  const std::string no_uvs =
      test::scene_error_of([&] { load_scene_json(bare, "scene.json", dir_.string()); });
  EXPECT_NE(no_uvs.find("shapes[0].material"), std::string::npos) << no_uvs;
  EXPECT_NE(no_uvs.find("bare.obj' has no texture coordinates"), std::string::npos) << no_uvs;
}

// An 8-bit grey PNG of one value v: as a roughness texture it is data, v / 255, whatever its
// colour space; as an albedo texture the same file is an sRGB colour, decoded. A roughness
// texture makes roughness a factor, 1 by default, for dielectrics and conductors alike, and the
// canonical form keeps it.
TEST_F(TextureTest, RoughnessTexturesAreDataWithAUnitFactor) {
  const std::string png = (dir_ / "grey.png").string();
  const unsigned char pixels[4] = {128, 128, 128, 128};
  ASSERT_TRUE(test::write_uint8_image(png, 2, 2, 1, pixels));
  json doc = textured_quad_scene({{"type", "dielectric"}, {"roughness_texture", "grey.png"}});
  doc["materials"] = {{{"name", "brushed"},
                       {"type", "conductor"},
                       {"metal", "gold"},
                       {"roughness", 0.3},
                       {"roughness_texture", "grey.png"}},
                      {{"name", "painted"}, {"type", "diffuse"}, {"albedo_texture", "grey.png"}}};
  doc["shapes"].push_back({{"type", "quad"}, {"size", 1.0}, {"material", "brushed"}});
  doc["shapes"].push_back({{"type", "quad"}, {"size", 0.5}, {"material", "painted"}});
  const LoadedScene loaded = load_scene_json(doc, "textures", dir_.string());
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.textures.size(), 2u) << "one file, read as data and as a colour";
  const Material& glass = scene.materials[static_cast<size_t>(scene.shapes[0].material)];
  const Material& gold = scene.materials[static_cast<size_t>(scene.shapes[1].material)];
  const Material& paint = scene.materials[static_cast<size_t>(scene.shapes[2].material)];
  EXPECT_EQ(glass.kind, MaterialKind::kDielectric);
  EXPECT_EQ(glass.roughness, 1.0f);
  EXPECT_EQ(gold.roughness, 0.3f);
  ASSERT_GE(glass.roughness_texture, 0);
  EXPECT_EQ(glass.roughness_texture, gold.roughness_texture);
  EXPECT_FALSE(glass.roughness_texture_squared);
  const Rgb data = scene.textures[static_cast<size_t>(glass.roughness_texture)].image.pixels[0];
  const Rgb colour = scene.textures[static_cast<size_t>(paint.albedo_texture)].image.pixels[0];
  expect_rgb(data, Rgb(128.0f / 255.0f), 1e-6f, "data");
  // sRGB 128/255 is linear 0.2158.
  expect_rgb(colour, Rgb(0.21586f), 1e-4f, "colour");
  const json canonical = loaded.canonical;
  bool kept = false;
  for (const json& m : canonical["materials"]) {
    if (m.contains("roughness_texture")) kept = m["roughness_texture"].get<std::string>() == png;
  }
  EXPECT_TRUE(kept) << canonical.dump();
  const LoadedScene again = load_scene_json(canonical, "canonical", dir_.string());
  EXPECT_EQ(again.canonical, canonical);
}

// An alpha channel is ignored: an 8-bit RGBA PNG texel of alpha 0 keeps its colour (OpenImageIO
// would otherwise multiply alpha into it), as a colour texture and as data.
TEST_F(TextureTest, AlphaIsIgnored) {
  const std::string png = (dir_ / "cutout.png").string();
  const unsigned char pixels[8] = {128, 64, 255, 0, 128, 64, 255, 255};
  ASSERT_TRUE(test::write_uint8_image(png, 2, 1, 4, pixels));
  json doc = textured_quad_scene({{"type", "diffuse"}, {"albedo_texture", "cutout.png"}});
  doc["shapes"].push_back(
      {{"type", "quad"},
       {"size", 1.0},
       {"material",
        {{"type", "conductor"}, {"metal", "gold"}, {"roughness_texture", "cutout.png"}}}});
  const Scene scene = load_scene_json(doc, "textures", dir_.string()).scene;
  ASSERT_EQ(scene.textures.size(), 2u);
  for (const Texture& t : scene.textures) {
    expect_rgb(t.image.pixels[0], t.image.pixels[1], 0, t.image.source + " alpha 0 and 1");
  }
  const auto& data =
      scene.materials[static_cast<size_t>(scene.shapes[1].material)].roughness_texture;
  expect_rgb(scene.textures[static_cast<size_t>(data)].image.pixels[0],
             Rgb(128.0f / 255, 64.0f / 255, 1.0f), 1e-6f, "data");
}

// Images inside a .glb have no file: decoding from memory must not fall back to opening the
// name as a path (it did once the reader got a configuration, making it ignore the proxy).
TEST_F(TextureTest, ImagesDecodeFromMemoryUnderANameThatIsNoFile) {
  const std::string png = (dir_ / "cutout.png").string();
  const unsigned char pixels[4] = {200, 100, 50, 0};
  ASSERT_TRUE(test::write_uint8_image(png, 1, 1, 4, pixels));
  std::ifstream in(png, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const RgbImage image = decode_rgb_image(bytes, "asset.glb: images[0].png", "texture",
                                          MemoryBudget{}, PixelValues::kData);
  ASSERT_EQ(image.pixels.size(), 1u);
  expect_rgb(image.pixels[0], Rgb(200.0f / 255, 100.0f / 255, 50.0f / 255), 1e-6f, "from memory");
}

// A medium's albedo_texture is one albedo for the whole medium: the image's mean colour, times
// `albedo` where given.
TEST_F(TextureTest, MediumAlbedoTextureIsTheMeanOfTheImage) {
  json doc = textured_quad_scene({{"type", "diffuse"}});
  doc["media"] = {
      {{"name", "painted"}, {"albedo_texture", "quadrants.exr"}, {"mean_free_path", 0.5}},
      {{"name", "dimmed"},
       {"albedo_texture", "quadrants.exr"},
       {"albedo", 0.5},
       {"mean_free_path", 0.5}}};
  const Scene scene = load_scene_json(doc, "textures", dir_.string()).scene;
  const Rgb mean =
      (quadrant_colour(0) + quadrant_colour(1) + quadrant_colour(2) + quadrant_colour(3)) * 0.25f;
  ASSERT_EQ(scene.media.size(), 2u);
  expect_rgb(scene.media[0].sigma_s, mean * 2.0f, 1e-6f, "sigma_s");
  expect_rgb(scene.media[0].sigma_t(), Rgb(2.0f), 1e-6f, "sigma_t");
  expect_rgb(scene.media[1].sigma_s, mean, 1e-6f, "sigma_s with a factor");
  EXPECT_TRUE(scene.textures.empty()) << "a medium's texture is not looked up while rendering";

  doc["media"] = {{{"name", "bright"}, {"albedo_texture", "quadrants.exr"}}};
  const std::string missing =
      test::scene_error_of([&] { load_scene_json(doc, "scene.json", dir_.string()); });
  EXPECT_NE(missing.find("media[0]"), std::string::npos) << missing;
  EXPECT_NE(missing.find("mean_free_path"), std::string::npos) << missing;
  doc["media"] = {{{"name", "gone"}, {"albedo_texture", "nope.exr"}, {"mean_free_path", 1}}};
  const std::string absent =
      test::scene_error_of([&] { load_scene_json(doc, "scene.json", dir_.string()); });
  EXPECT_NE(absent.find("media[0].albedo_texture"), std::string::npos) << absent;
  EXPECT_NE(absent.find("nope.exr"), std::string::npos) << absent;
}

Vec3 on_sphere(const Shape& sphere, float theta, float phi) {
  return sphere.center + sphere.radius * Vec3(std::sin(theta) * std::sin(phi), std::cos(theta),
                                              std::sin(theta) * std::cos(phi));
}

// The globe mapping of surface_uv.h: +z faces the image centre, +y is its top row, +x is to
// the right of the centre.
TEST(SphereUv, MapsLikeAGlobeSeenFromOutside) {
  Shape sphere;
  sphere.kind = ShapeKind::kSphere;
  sphere.center = Vec3(1, -2, 3);
  sphere.radius = 2;
  const struct {
    Vec3 direction;
    float u, v;
  } cases[] = {{{0, 0, 1}, 0.5f, 0.5f},         {{1, 0, 0}, 0.75f, 0.5f},
               {{-1, 0, 0}, 0.25f, 0.5f},       {{0, 1, 0}, 0.5f, 0.0f},
               {{0, -1, 0}, 0.5f, 1.0f},        {{0, 0.5f, 0.5f}, 0.5f, 0.25f},
               {{0.5f, 0, -0.5f}, 0.875f, 0.5f}};
  for (const auto& c : cases) {
    const Vec3 p = sphere.center + sphere.radius * normalize(c.direction);
    const SurfaceUv at = surface_uv(sphere, 0, p);
    EXPECT_NEAR(at.uv.u, c.u, 1e-6f)
        << c.direction.x << " " << c.direction.y << " " << c.direction.z;
    EXPECT_NEAR(at.uv.v, c.v, 1e-6f)
        << c.direction.x << " " << c.direction.y << " " << c.direction.z;
  }
}

// per_length is the square root of the texture area over the surface area of a small patch,
// measured here on patches of 1e-3 x 1e-3 radians at several latitudes (rate at their centres).
TEST(SphereUv, RateIsTheSquareRootOfTheAreaRatio) {
  Shape sphere;
  sphere.kind = ShapeKind::kSphere;
  sphere.radius = 0.5f;
  const float h = 1e-3f;
  for (const float theta : {0.1f, 0.5f, 1.0f, 1.5707964f, 2.5f}) {
    const float phi = 0.3f;
    const Uv a = sphere_uv(sphere, on_sphere(sphere, theta, phi));
    const Uv b = sphere_uv(sphere, on_sphere(sphere, theta + h, phi + h));
    const double uv_area = std::fabs(double(b.u - a.u) * double(b.v - a.v));
    const double area =
        double(sphere.radius) * sphere.radius * std::sin(theta + 0.5 * h) * double(h) * h;
    const float rate =
        surface_uv(sphere, 0, on_sphere(sphere, theta + 0.5f * h, phi + 0.5f * h)).per_length;
    EXPECT_NEAR(rate, std::sqrt(uv_area / area), 2e-3 * rate) << "theta " << theta;
  }
}

}  // namespace
}  // namespace snee
