#include "scene/texture_set.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <string>

#include "scene/scene_error.h"

namespace snee {

namespace {

// The ImageInput that the cache opens for a texture: it serves the rows of an RgbImage in
// memory, whose address comes in the open() configuration (the cache's creator takes no
// argument to carry it).
class MemoryImageInput final : public OIIO::ImageInput {
 public:
  static constexpr const char* kPixelsAttribute = "snee:pixels";

  const char* format_name() const override { return "snee-memory"; }

  bool open(const std::string&, OIIO::ImageSpec&) override {
    errorfmt("a snee texture opens only with its pixels in the configuration");
    return false;
  }

  bool open(const std::string&, OIIO::ImageSpec& spec, const OIIO::ImageSpec& config) override {
    const OIIO::ParamValue* pixels = config.find_attribute(kPixelsAttribute, OIIO::TypeDesc::PTR);
    if (!pixels) return open("", spec);
    image_ = *static_cast<const RgbImage* const*>(pixels->data());
    m_spec = OIIO::ImageSpec(image_->width, image_->height, 3, OIIO::TypeDesc::FLOAT);
    spec = m_spec;
    return true;
  }

  bool read_native_scanline(int subimage, int miplevel, int y, int, void* data) override {
    if (subimage != 0 || miplevel != 0 || y < 0 || y >= image_->height) return false;
    std::memcpy(data, &image_->pixels[static_cast<size_t>(y) * image_->width],
                sizeof(Rgb) * static_cast<size_t>(image_->width));
    return true;
  }

  bool close() override { return true; }

 private:
  const RgbImage* image_ = nullptr;
};

OIIO::ImageInput* create_memory_image_input() {
  return new MemoryImageInput;
}

OIIO::TextureOpt::Wrap oiio_wrap(TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::kMirror:
      return OIIO::TextureOpt::WrapMirror;
    case TextureWrap::kClamp:
      return OIIO::TextureOpt::WrapClamp;
    default:
      return OIIO::TextureOpt::WrapPeriodic;
  }
}

}  // namespace

struct TextureSet::Impl {
  OIIO::TextureSystem* system = nullptr;
  std::vector<OIIO::ustring> names;  // by texture
  std::vector<OIIO::TextureSystem::TextureHandle*> handles;
  std::vector<OIIO::TextureOpt> options;  // by texture
};

TextureSet::TextureSet(const std::vector<Texture>& textures) : impl_(std::make_unique<Impl>()) {
  // The process-wide system, never destroyed: OpenImageIO 2.4's TextureSystem::destroy deletes
  // its implementation through the base class (AddressSanitizer: new-delete-type-mismatch).
  // Each set's textures get names no other set uses and are dropped from the cache with it.
  impl_->system = OIIO::TextureSystem::create(/*shared=*/true);
  OIIO::TextureSystem& system = *impl_->system;
  // The levels are made in memory from the finest one (automip); rows are cut into 64x64 tiles
  // (autotile), the unit the cache keeps and evicts.
  system.attribute("automip", 1);
  system.attribute("autotile", 64);
  for (size_t i = 0; i < textures.size(); ++i) {
    // The name only identifies the texture to the cache (a file of that name is never read,
    // since the creator serves the pixels); the count makes it unique in the process, so a name
    // never refers to the pixels of a set already gone.
    static std::atomic<uint64_t> next_name{0};
    const OIIO::ustring name("snee-texture:" + std::to_string(next_name++));
    impl_->names.push_back(name);
    OIIO::ImageSpec config;
    const RgbImage* image = &textures[i].image;
    config.attribute(MemoryImageInput::kPixelsAttribute, OIIO::TypeDesc::PTR, &image);
    if (!system.imagecache()->add_file(name, &create_memory_image_input, &config)) {
      throw SceneError(textures[i].image.source +
                       ": cannot set up the texture: " + system.geterror());
    }
    impl_->handles.push_back(system.get_texture_handle(name));
    OIIO::TextureOpt options;
    options.swrap = oiio_wrap(textures[i].wrap_u);
    options.twrap = oiio_wrap(textures[i].wrap_v);
    options.interpmode = OIIO::TextureOpt::InterpBilinear;
    options.mipmode = OIIO::TextureOpt::MipModeTrilinear;
    impl_->options.push_back(options);
    // One lookup now makes the cache open the texture and build its levels, so that a texture
    // the system cannot use is a loading error rather than black pixels in the render.
    float rgb[3];
    if (!system.texture(impl_->handles.back(), nullptr, options, 0.5f, 0.5f, 1.0f, 0, 0, 1.0f, 3,
                        rgb)) {
      throw SceneError(textures[i].image.source + ": cannot use the texture: " + system.geterror());
    }
  }
}

TextureSet::~TextureSet() {
  for (const OIIO::ustring& name : impl_->names) impl_->system->invalidate(name, /*force=*/true);
}

Rgb TextureSet::lookup(int texture, Uv uv, float width) const {
  float rgb[3] = {0, 0, 0};
  // The lookup takes its options by non-const reference, so each gets its own copy.
  OIIO::TextureOpt options = impl_->options[static_cast<size_t>(texture)];
  if (!impl_->system->texture(impl_->handles[static_cast<size_t>(texture)], nullptr, options, uv.u,
                              uv.v, width, 0, 0, width, 3, rgb)) {
    // Every texture was looked up once by the constructor, so this is not reached with the
    // pixels in memory; the error is taken so it does not pile up in the thread's state.
    (void)impl_->system->geterror();
    return Rgb(0.0f);
  }
  return {rgb[0], rgb[1], rgb[2]};
}

}  // namespace snee
