// `snee compare`: how it spends an equal-time budget, the contact sheet's layout, labels and
// colour bar, and the command as a user meets it (inputs checked before anything renders, the
// report's time bookkeeping agreeing with the files).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <OpenImageIO/imagebuf.h>

#include "apps/contact_sheet.h"
#include "apps/equal_time_plan.h"
#include "apps/image_error.h"
#include "apps/labelled_preview.h"
#include "scene/film.h"
#include "tests/support/snee_directory.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

TEST(EqualTimePlan, RoundsAreShortAndTheClockStopsHalfARoundEarly) {
  struct Case {
    double budget, per_spp;
  };
  for (const Case c : {Case{10, 1e-3}, Case{10, 0.02}, Case{10, 0.05}, Case{2, 0.5}, Case{1, 3.0},
                       Case{3600, 1e-7}}) {
    const EqualTimePlan plan = plan_equal_time(c.budget, c.per_spp);
    const double round = plan.samples_per_unit * c.per_spp;
    EXPECT_GE(plan.samples_per_unit, 1);
    EXPECT_LE(plan.samples_per_unit, kLongestRoundSpp);
    // As long as rounds may be, but no longer than the share of the budget allows (a round of
    // one spp is the shortest there is).
    if (plan.samples_per_unit > 1) {
      EXPECT_LE(round, kRoundShareOfBudget * c.budget);
    }
    if (plan.samples_per_unit < kLongestRoundSpp) {
      EXPECT_GT(round + c.per_spp, kRoundShareOfBudget * c.budget);
    }
    EXPECT_NEAR(plan.time_seconds, std::max(c.budget - 0.5 * round, 1e-9), 1e-12 * c.budget);
    EXPECT_GT(plan.time_seconds, 0);
    EXPECT_EQ(plan.max_spp % plan.samples_per_unit, 0) << "whole rounds";
    // Room for the machine to get faster than the pilots saw, within the renderer's range.
    EXPECT_GE(plan.max_spp, std::min(kSppHeadroom * c.budget / c.per_spp,
                                     double{kMaxEqualTimeSpp - kLongestRoundSpp}));
    EXPECT_LE(plan.max_spp, kMaxEqualTimeSpp);
  }
}

TEST(EqualTimePlan, WithinBudgetIsFivePercentEitherWay) {
  EXPECT_TRUE(within_budget(10.0, 10.0));
  EXPECT_TRUE(within_budget(10.49, 10.0));
  EXPECT_TRUE(within_budget(9.51, 10.0));
  EXPECT_FALSE(within_budget(10.51, 10.0));
  EXPECT_FALSE(within_budget(9.49, 10.0));
}

class LabelFont : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("compare"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(LabelFont, FirstExistingCandidateWinsAndNoneIsNoFont) {
  const fs::path present = dir_ / "b.ttf", also = dir_ / "c.ttf";
  std::ofstream(present) << "x";
  std::ofstream(also) << "x";
  EXPECT_EQ(find_label_font({dir_ / "a.ttf", present, also}), present);
  EXPECT_EQ(find_label_font({dir_ / "a.ttf", dir_}), std::nullopt) << "a directory is no font";
  EXPECT_EQ(find_label_font({}), std::nullopt);
}

TEST_F(LabelFont, AFileThatIsNoFontIsRefusedByName) {
  const fs::path fake = dir_ / "fake.ttf";
  std::ofstream(fake) << "not a font";
  try {
    check_label_font(fake);
    FAIL() << "a text file was accepted as a font";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fake.string()), std::string::npos) << e.what();
  }
}

Film flat(int w, int h, float value) {
  Film f;
  f.width = w;
  f.height = h;
  f.mean.assign(static_cast<size_t>(w) * h, Rgb(value));
  return f;
}

TEST(ContactSheet, TilesAreZoomedWholeSplitAndLabelledWithAColourBar) {
  const int w = 12, h = 9;
  const Film reference = flat(w, h, 0.5f), first = flat(w, h, 0.25f), second = flat(w, h, 0.75f);
  const Film error_a = flat(w, h, 0.1f), error_b = flat(w, h, 0.9f);
  const std::vector<SheetRender> renders = {{"pt", &first, error_a, 16, 1.5, 0.25},
                                            {"snee", &second, error_b, 7, 1.25, 0.125}};
  const ContactSheet sheet = contact_sheet(reference, "reference: snee, 64 spp", renders);
  const int z = sheet.zoom;
  EXPECT_EQ(z, (kMinSheetTileWidth + w - 1) / w);
  const int tw = w * z, th = h * z;
  const Film& image = sheet.image;
  EXPECT_EQ(image.width, 2 * tw + 4);
  ASSERT_EQ(image.mean.size(), static_cast<size_t>(image.width) * image.height);
  // The split view: the first render's left half, the second's right half, each image pixel a
  // z x z block; the reference beside it.
  EXPECT_EQ(image.at(0, 0)[0], 0.25f);
  EXPECT_EQ(image.at(w / 2 * z - 1, th - 1)[0], 0.25f);
  EXPECT_EQ(image.at(w / 2 * z, 0)[0], 0.75f);
  EXPECT_EQ(image.at(tw - 1, th - 1)[0], 0.75f);
  EXPECT_EQ(image.at(tw + 4, 0)[0], 0.5f);
  EXPECT_EQ(image.at(2 * tw + 3, th - 1)[0], 0.5f);
  // The error maps in order in the second row, below the first row's labels.
  const auto first_in_column = [&](int x, float value) {
    for (int y = th; y < image.height; ++y)
      if (image.at(x, y)[0] == value) return y;
    return -1;
  };
  const int row = first_in_column(0, 0.1f);
  ASSERT_GT(row, th);
  EXPECT_EQ(first_in_column(tw + 4, 0.9f), row);
  EXPECT_EQ(image.at(tw - 1, row + th - 1)[0], 0.1f);
  // The colour bar runs the scale from its lowest to its highest decade, left to right.
  const int bar_y = image.height - 2 * kLabelLineHeight;
  const Rgb low = error_colour(std::pow(10.0, kErrorMapLowestDecade));
  const Rgb high = error_colour(std::pow(10.0, kErrorMapHighestDecade));
  int bar_begin = -1, bar_end = -1;
  for (int x = 0; x < image.width; ++x) {
    const Rgb& c = image.at(x, bar_y);
    if (bar_begin < 0 && c[0] == low[0] && c[1] == low[1] && c[2] == low[2]) bar_begin = x;
    if (c[0] == high[0] && c[1] == high[1] && c[2] == high[2]) bar_end = x;
  }
  ASSERT_GE(bar_begin, 0) << "no bar at y " << bar_y;
  EXPECT_GT(bar_end, bar_begin + image.width / 2);
  // Every tile says what it is; the bar has a label per decade; all inside the sheet.
  std::vector<std::string> texts;
  for (const TextLabel& label : sheet.labels) {
    texts.push_back(label.text);
    EXPECT_GE(label.clip_begin, 0);
    EXPECT_LE(label.clip_end, image.width);
    EXPECT_LT(label.clip_begin, label.clip_end);
    EXPECT_GT(label.y, 0);
    EXPECT_LT(label.y, image.height);
  }
  const auto has = [&](const std::string& text) {
    return std::find(texts.begin(), texts.end(), text) != texts.end();
  };
  EXPECT_TRUE(has("left: pt   right: snee"));
  EXPECT_TRUE(has("reference: snee, 64 spp"));
  EXPECT_TRUE(has("pt: 16 spp, 1.50 s"));
  EXPECT_TRUE(has("snee: 7 spp, 1.25 s"));
  EXPECT_TRUE(has("relMSE 0.25 (error map)"));
  EXPECT_TRUE(has("relMSE 0.125 (error map)"));
  for (int d = kErrorMapLowestDecade; d <= kErrorMapHighestDecade; ++d)
    EXPECT_TRUE(has("1e" + std::to_string(d))) << d;
}

// Reads an 8-bit image back as floats in [0, 1].
std::vector<float> read_pixels(const fs::path& file, int& width, int& height) {
  OIIO::ImageBuf buffer(file.string());
  EXPECT_TRUE(buffer.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << buffer.geterror();
  width = buffer.spec().width;
  height = buffer.spec().height;
  std::vector<float> pixels(static_cast<size_t>(width) * height * 3);
  buffer.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pixels.data());
  return pixels;
}

TEST_F(LabelFont, LabelsAreDrawnWhiteInsideTheirClipAndLeftOutWithoutAFont) {
  const std::optional<fs::path> font = find_label_font(default_label_fonts());
  if (!font) GTEST_SKIP() << "no DejaVu Sans installed (scripts/setup.sh installs it)";
  const Film black = flat(120, 40, 0.0f);
  // The text would run past column 60, where its clip ends.
  const std::vector<TextLabel> labels = {{2, 20, "WWWWWWWWWWWWWWWWWWWW", 0, 60, false}};
  const fs::path with = dir_ / "with.png", without = dir_ / "without.png";
  write_labelled_preview(black, labels, font, with);
  write_labelled_preview(black, labels, std::nullopt, without);
  int w = 0, h = 0;
  const std::vector<float> drawn = read_pixels(with, w, h);
  ASSERT_EQ(w, 120);
  ASSERT_EQ(h, 40);
  float brightest = 0, outside_clip = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = drawn[(static_cast<size_t>(y) * w + x) * 3];
      (x < 60 ? brightest : outside_clip) = std::max(x < 60 ? brightest : outside_clip, v);
    }
  EXPECT_EQ(brightest, 1.0f) << "white text";
  EXPECT_EQ(outside_clip, 0.0f) << "text past its clip";
  const std::vector<float> plain = read_pixels(without, w, h);
  EXPECT_EQ(*std::max_element(plain.begin(), plain.end()), 0.0f);
}

class CompareCli : public test::SneeDirectoryTest {
 protected:
  CompareCli() : SneeDirectoryTest("compare_cli") {}
  int snee(const std::string& args) const { return run(SNEE_BINARY, args); }
};

// The report's time of each render is the one its EXR records, its spp the rounds it holds,
// and the share of the budget and the verdict on it follow from them. (How close to the
// budget a render comes depends on the machine; scripts/ and the closing notes measure it.)
TEST_F(CompareCli, EqualTimeBookkeepingAgreesWithTheImages) {
  const double budget = 0.4;
  ASSERT_EQ(snee("compare builtin:sphere-cone-r0.2 --resolution 16x16 --time 0.4 "
                 "--reference-spp 8 --threads 2 -o cmp"),
            0)
      << output();
  EXPECT_TRUE(said("reference snee: 8 spp in")) << output();
  EXPECT_TRUE(said("pt pilot: 2 spp in")) << output();
  const auto report = nlohmann::json::parse(test::read_text_file(path("cmp/compare.json")));
  EXPECT_EQ(report["mode"], "equal-time");
  EXPECT_EQ(report["budget_seconds"], budget);
  EXPECT_EQ(report["budget_tolerance"], kBudgetTolerance);
  ASSERT_EQ(report["integrators"].size(), 2u);
  for (const auto& entry : report["integrators"]) {
    const Film film = read_exr(path("cmp/" + entry["name"].get<std::string>() + ".exr"));
    const double seconds = entry["seconds"];
    EXPECT_EQ(seconds, film.meta.render_seconds);
    EXPECT_EQ(entry["spp"], film.meta.min_spp);
    EXPECT_GT(film.meta.time_budget_seconds, 0.0);
    EXPECT_LE(film.meta.time_budget_seconds, budget);
    const int round = entry["samples_per_round"];
    EXPECT_GE(round, 1);
    EXPECT_LE(round, kLongestRoundSpp);
    EXPECT_EQ(film.meta.min_spp % round, 0) << "whole rounds";
    EXPECT_LE(film.meta.min_spp, film.meta.spp);
    EXPECT_DOUBLE_EQ(entry["budget_share"].get<double>(), seconds / budget);
    EXPECT_EQ(entry["within_budget"].get<bool>(), within_budget(seconds, budget));
    EXPECT_LE(entry["sampling_seconds"].get<double>(), seconds);
  }
  EXPECT_TRUE(fs::is_regular_file(path("cmp/contact-sheet.png")));
  const auto& sheet = report["contact_sheet"];
  EXPECT_EQ(sheet["labels"].get<bool>(), !sheet["font"].get<std::string>().empty());
}

// Wrong inputs are found before the first sample: nothing is rendered or written.
TEST_F(CompareCli, BadReferenceOrFontStopsBeforeRendering) {
  ASSERT_EQ(snee("render builtin:sphere-cone-r0.2 --resolution 12x12 --spp 1 --quiet -o r.exr"), 0)
      << output();
  EXPECT_EQ(snee("compare builtin:sphere-cone-r0.2 --resolution 8x8 --time 600 --reference r.exr "
                 "-o cmp"),
            1);
  EXPECT_TRUE(said("the reference is 12x12 but the renders would be 8x8")) << output();
  EXPECT_TRUE(said("give --resolution 12x12")) << output();
  EXPECT_FALSE(said("pilot")) << output();
  EXPECT_FALSE(fs::exists(path("cmp/pt.exr")));

  std::ofstream(path("fake.ttf")) << "not a font";
  EXPECT_EQ(snee("compare builtin:sphere-cone-r0.2 --resolution 12x12 --time 600 --reference "
                 "r.exr --font fake.ttf -o cmp"),
            1);
  EXPECT_TRUE(said("cannot draw text with the font 'fake.ttf'")) << output();
  EXPECT_FALSE(said("pilot")) << output();
}

}  // namespace
}  // namespace snee
