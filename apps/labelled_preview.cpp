#include "apps/labelled_preview.h"

#include <stdexcept>
#include <system_error>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "apps/output_files.h"

namespace snee {

namespace fs = std::filesystem;

std::vector<fs::path> default_label_fonts() {
  return {
      "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf",
      "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"};
}

std::optional<fs::path> find_label_font(const std::vector<fs::path>& candidates) {
  for (const fs::path& font : candidates) {
    std::error_code error;
    if (fs::is_regular_file(font, error)) return font;
  }
  return std::nullopt;
}

void check_label_font(const fs::path& font) {
  OIIO::ImageBuf probe(OIIO::ImageSpec(32, 32, 3, OIIO::TypeDesc::FLOAT));
  if (!OIIO::ImageBufAlgo::render_text(probe, 2, 20, "1e-4", kLabelFontSize, font.string()))
    throw std::invalid_argument("cannot draw text with the font '" + font.string() +
                                "': " + probe.geterror());
}

void write_labelled_preview(const Film& image, const std::vector<TextLabel>& labels,
                            const std::optional<fs::path>& font, const fs::path& path,
                            const ToneMap& tone) {
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("Software", "snee " SNEE_VERSION);
  OIIO::ImageBuf buffer(spec);
  std::vector<float> pixels;
  pixels.reserve(image.mean.size() * 3);
  for (const Rgb& rgb : image.mean)
    for (int c = 0; c < 3; ++c) pixels.push_back(tone.encode(rgb[c]));
  buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pixels.data());
  if (font) {
    const std::string font_name = font->string();
    for (const TextLabel& label : labels) {
      // render_text draws past its ROI, so each label is drawn into a cut of its clip and
      // pasted back.
      const OIIO::ROI clip(label.clip_begin, label.clip_end, 0, image.height, 0, 1, 0, 3);
      OIIO::ImageBuf part = OIIO::ImageBufAlgo::cut(buffer, clip);
      const auto align = label.centred ? OIIO::ImageBufAlgo::TextAlignX::Center
                                       : OIIO::ImageBufAlgo::TextAlignX::Left;
      if (!OIIO::ImageBufAlgo::render_text(part, label.x - label.clip_begin, label.y, label.text,
                                           kLabelFontSize, font_name, {1.0f, 1.0f, 1.0f}, align) ||
          !OIIO::ImageBufAlgo::paste(buffer, label.clip_begin, 0, 0, 0, part))
        throw std::runtime_error("cannot draw text in font '" + font_name +
                                 "': " + part.geterror() + buffer.geterror());
    }
  }
  replace_file(path, [&](const std::string& partial) {
    if (!buffer.write(partial, OIIO::TypeDesc::UINT8))
      throw std::runtime_error("cannot write image '" + partial + "': " + buffer.geterror());
  });
}

}  // namespace snee
