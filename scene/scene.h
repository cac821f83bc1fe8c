// The scene description: plain data that says *what* is rendered (camera, shapes, materials,
// media, lights, render settings), with no knowledge of *how*. Loaders fill it; the Embree
// scene and the kernels' light tables are built from it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/density_grid.h"
#include "core/math.h"
#include "scene/light_selection.h"

namespace snee {

// Largest magnitude of any world-space coordinate: the camera's position and look_at, mesh
// vertices after their transform, sphere centre +- radius, point-light positions. Within it, a
// difference of two points is below 2e12 per axis (3.5e12 long), so the products of three such
// lengths that ray-triangle tests form (an edge cross product dotted with an offset) stay below
// 4.2e37, under float's 3.4e38, and every ray origin and direction keeps far inside the range
// Embree accepts (|x| < 1.8e18; beyond it Embree aborts on an invalid ray).
inline constexpr float kMaxCoordinate = 1e12f;

// Brightest light a scene may hold: an emission, radiance, irradiance or intensity per channel
// (an environment light's scale times its brightest pixel). Path throughputs rarely exceed
// 1e8 (refraction's eta^2 per crossing, 1/pdf of a grazing sample), so a sample stays below
// float's 3.4e38 and a film of them stays finite: brighter lights only ever produced
// non-finite samples. glTF lights and emissive strengths have the same bound.
inline constexpr double kMaxBrightness = 1e30;

// Longest image edge in pixels, for a scene's camera resolution and the command line's
// --resolution alike: a width * height pixel index (at most 2^30) fits an int.
inline constexpr int kMaxImageEdge = 1 << 15;

// The image edge a camera's field of view spans; the other edge follows from the aspect ratio,
// so a new resolution keeps the angle along this one.
enum class FovAxis : uint8_t { kVertical, kHorizontal, kDiagonal };

// A thin lens: rays start on a disk of aperture_radius around position, perpendicular to the
// viewing direction, and meet in the plane focus_distance in front of it. Aperture 0 is a
// pinhole, and then focus_distance has no effect.
struct Camera {
  Vec3 position{0, 0, 5};
  Vec3 look_at{0, 0, 0};
  Vec3 up{0, 1, 0};
  float fov_degrees = 40.0f;  // along fov_axis
  FovAxis fov_axis = FovAxis::kVertical;
  float aperture_radius = 0.0f;  // world units
  float focus_distance = 0.0f;   // world units; 0: the distance from position to look_at
  int width = 256;
  int height = 256;
};

enum class MaterialKind : uint8_t {
  kDiffuse,     // Lambertian, two-sided
  kDielectric,  // Fresnel interface; roughness 0 = smooth, otherwise GGX alpha used directly
  kNull,        // index-matched interface: only bounds a medium, invisible to every ray
  kConductor,   // metal: complex-index Fresnel, GGX alpha = roughness (0: mirror), two-sided
  kDiffuseTransmission,  // thin sheet: Lambertian reflection (albedo) and transmission
};

// Whether light can pass the surface into a medium it bounds (a diffuse transmitter is a sheet
// with the same medium on both sides, so it bounds none).
inline bool bounds_media(MaterialKind kind) {
  return kind == MaterialKind::kDielectric || kind == MaterialKind::kNull;
}

struct Material {
  std::string name;
  MaterialKind kind = MaterialKind::kDiffuse;
  Rgb albedo{0.5f};         // diffuse; the reflectance of a diffuse transmitter
  Rgb transmittance{0.0f};  // diffuse transmitter; albedo + transmittance <= 1 per channel
  float ior = 1.5f;         // dielectric: interior index / exterior index
  float roughness = 0.0f;   // dielectric and conductor: GGX alpha
  Rgb conductor_eta{0.0f};  // conductor: complex index eta + i k relative to the exterior
  Rgb conductor_k{1.0f};
  // Diffuse and diffuse transmitter: index into Scene::textures whose colour, looked up at the
  // hit's texture coordinates, multiplies `albedo`; -1 for none. Only meshes with texture
  // coordinates may carry such a material (the loader checks).
  int albedo_texture = -1;
  // Dielectric and conductor: index into Scene::textures whose green channel g (where glTF's
  // metallic-roughness textures keep roughness; a grey image has it in every channel), looked up
  // at the hit, scales `roughness`: the GGX alpha there is roughness * g, or roughness * g^2 when
  // `roughness_texture_squared` (glTF, whose alpha is the square of its perceptual roughness, so
  // that `roughness` holds roughnessFactor^2). -1 for none.
  int roughness_texture = -1;
  bool roughness_texture_squared = false;
  bool has_texture() const { return albedo_texture >= 0 || roughness_texture >= 0; }
};

// Participating medium; coefficients per scene unit. Homogeneous unless it has a density grid,
// which then scales sigma_s and sigma_a point by point (they are the coefficients at density 1).
struct Medium {
  std::string name;
  Rgb sigma_s{1.0f};
  Rgb sigma_a{0.0f};
  float g = 0.0f;  // Henyey-Greenstein asymmetry
  std::shared_ptr<const DensityGrid> density;
  Rgb sigma_t() const { return sigma_s + sigma_a; }
};

// Texture coordinates in image terms, as glTF and OpenImageIO have them: u runs right, v down,
// (0, 0) is the top-left corner of the image's first pixel and (1, 1) the bottom-right corner of
// its last; outside [0, 1) a texture repeats, mirrors or clamps (Texture). OBJ's v runs up and
// is flipped when read.
struct Uv {
  float u = 0, v = 0;
};

// World-space triangle mesh with outward-facing winding (counter-clockwise seen from outside).
// Normals and texture coordinates, where the file has them, are one per position; normals are
// interpolated for smooth shading (Shape::smooth_shading), texture coordinates for textures
// (Material::albedo_texture).
struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<Vec3> normals;      // empty or positions.size(), unit, world space
  std::vector<Uv> uvs;            // empty or positions.size()
  size_t triangle_count() const { return indices.size() / 3; }
};

enum class ShapeKind : uint8_t { kMesh, kSphere };

struct Shape {
  std::string name;
  ShapeKind kind = ShapeKind::kMesh;
  TriangleMesh mesh;         // kMesh (quads and planes are loaded as two-triangle meshes)
  Vec3 center;               // kSphere, world space
  float radius = 1;          // kSphere, world space
  int material = -1;         // index into Scene::materials
  int interior_medium = -1;  // index into Scene::media, -1 = none
  Rgb emission{0.0f};        // radiance leaving the front side; non-zero makes it an area light
  bool closed = true;        // false if the mesh has boundary edges (SNEE needs closed)
  // kMesh with normals: shade with the interpolated vertex normal (docs/method.md 4.9). The
  // geometric normal still decides sides and media.
  bool smooth_shading = false;
  std::string source;  // file it came from, for messages
};

enum class LightKind : uint8_t {
  kDirectional,  // delta in direction; irradiance on a surface facing it
  kCone,         // distant light of constant radiance within a cone ("solid-angle light")
  kConstantEnv,  // constant radiance from every direction
  kEnvMap,       // lat-long image, importance sampled
  kPoint,        // delta in position; intensity
  kSpot,         // delta in position; intensity along its axis, smoothly cut off at a cone
  kArea,         // emissive shape (Shape::emission), referenced by index
};

// An image in linear RGB: a lat-long environment map or a texture. Environment direction
// convention (y up): u = (atan2(d.x, -d.z) / (2 pi) + 0.5), v = acos(d.y) / pi; pixel (0,0) is at
// u=0, v=0 (top). The image centre looks along -z: Mitsuba 3's envmap turned 180 degrees about y
// (docs/lights.md, which also says how lookups filter). Textures: Uv below.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  // row-major, top row first
  std::string source;
};

// How a texture continues outside [0, 1) along one axis (glTF's sampler wrap modes).
enum class TextureWrap : uint8_t { kRepeat, kMirror, kClamp };

struct Texture {
  RgbImage image;
  TextureWrap wrap_u = TextureWrap::kRepeat, wrap_v = TextureWrap::kRepeat;
};

struct Light {
  LightKind kind = LightKind::kDirectional;
  Vec3 direction{0, 1, 0};   // unit, *toward* the light (directional and cone axis)
  Rgb irradiance{1.0f};      // directional
  float half_angle = 0;      // cone, radians
  Rgb radiance{1.0f};        // cone, constant env; scale for env map
  Vec3 position;             // point, spot
  Rgb intensity{1.0f};       // point, spot (on the axis)
  Vec3 spot_axis{0, -1, 0};  // spot: unit, the direction it shines (away from the light)
  // Spot: cosines of the cone's half-angle (nothing beyond) and of the angle where the falloff
  // starts (full intensity within); the intensity is smoothstep(cos_outer, cos_inner, cos).
  float spot_cos_outer = 0.0f, spot_cos_inner = 1.0f;
  int env_image = -1;      // kEnvMap: index into Scene::env_images
  Transform env_rotation;  // kEnvMap: world direction = env_rotation.vector(map direction)
  int shape = -1;          // kArea: index into Scene::shapes
};

// Defaults a scene may carry; the command line overrides them.
struct RenderSettings {
  int spp = 64;
  int max_depth = 1024;
  uint32_t seed = 0;
  std::string integrator = "pt";
  // Adaptive sampling's relative standard error (docs/budgets.md); 0: every pixel takes spp.
  double noise_target = 0;
  LightSelection light_selection = LightSelection::kUniform;
};

struct Scene {
  std::string name;
  Camera camera;
  std::vector<Material> materials;
  std::vector<Medium> media;
  std::vector<Shape> shapes;
  std::vector<Light> lights;
  std::vector<RgbImage> env_images;
  std::vector<Texture> textures;  // Material::albedo_texture
  RenderSettings render;
};

}  // namespace snee
