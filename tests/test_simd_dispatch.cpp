// Runtime SIMD dispatch: every level this machine can use renders the same bytes, so the level
// changes only the speed. The levels are those the CPU runs; where the build made the modules,
// every one of them must be found and load.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "scheduler/simd_dispatch.h"
#include "tests/support/render_helpers.h"
#include "tests/support/test_directory.h"

namespace snee {
namespace {

std::vector<SimdLevel> usable_levels() {
  std::vector<SimdLevel> levels;
  for (const SimdLevelStatus& s : simd_levels())
    if (s.usable) levels.push_back(s.level);
  return levels;
}

TEST(SimdDispatch, EveryLevelTheCpuRunsIsUsable) {
  const std::vector<SimdLevelStatus>& levels = simd_levels();
  ASSERT_EQ(levels.size(), std::size(kSimdLevels));
  EXPECT_TRUE(levels[static_cast<size_t>(kCompiledSimdLevel)].usable);
  EXPECT_EQ(levels[static_cast<size_t>(kCompiledSimdLevel)].detail, "built in");
  for (const SimdLevelStatus& s : levels) {
    const std::string name(simd_level_name(s.level));
    if (!cpu_runs(s.level)) {
      EXPECT_FALSE(s.usable) << name;
      EXPECT_EQ(s.detail, "this CPU lacks it") << name;
    } else if (simd_module_built(s.level) || s.level == kCompiledSimdLevel) {
      EXPECT_TRUE(s.usable) << name << ": " << s.detail;
    }
  }
  EXPECT_TRUE(simd_levels()[static_cast<size_t>(widest_simd_level())].usable);
  for (const SimdLevelStatus& s : levels) {
    if (s.usable) {
      EXPECT_LE(static_cast<int>(s.level), static_cast<int>(widest_simd_level()));
    }
  }
  std::string seen;
  for (const SimdLevel level : usable_levels()) seen += " " + std::string(simd_level_name(level));
  RecordProperty("usable_levels", seen);
  std::printf("usable SIMD levels here:%s\n", seen.c_str());
}

TEST(SimdDispatch, LevelNamesRoundTrip) {
  for (const SimdLevel level : kSimdLevels) {
    EXPECT_EQ(parse_simd_level(simd_level_name(level)), level);
    EXPECT_EQ(simd_level_description(level), std::string(simd_level_name(level)) + " (" +
                                                 std::to_string(simd_level_lanes(level)) +
                                                 " float lanes)");
  }
  EXPECT_FALSE(parse_simd_level("avx"));
  EXPECT_FALSE(parse_simd_level(""));
}

TEST(SimdDispatch, AnUnusableLevelIsRefusedSayingWhy) {
  for (const SimdLevelStatus& s : simd_levels()) {
    if (s.usable) continue;
    Scene scene = load_builtin_scene("default").scene;
    scene.camera.width = scene.camera.height = 8;
    RenderOptions o;
    o.spp = 1;
    o.simd = s.level;
    try {
      render(scene, o);
      ADD_FAILURE() << "rendered with unusable level " << simd_level_name(s.level);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string(simd_level_name(s.level))), std::string::npos) << what;
      EXPECT_NE(what.find(s.detail), std::string::npos) << what;
      EXPECT_NE(what.find("usable: sse4.2"), std::string::npos) << what;
    }
  }
}

// The loader's answers for a missing module, a file that is no module, and a module of another
// build, each naming the file; and the real module of a level the CPU runs.
TEST(SimdDispatch, ModulesAreCheckedBeforeUse) {
  const std::filesystem::path dir = test::fresh_test_directory("simd-modules");
  SimdModule missing = load_simd_module(SimdLevel::kAvx2, {dir});
  EXPECT_FALSE(missing.status.usable);
  EXPECT_EQ(missing.backend, nullptr);
  EXPECT_EQ(missing.status.detail, "not built: no snee-simd-avx2.so in " + dir.string());

  std::ofstream(dir / "snee-simd-avx2.so") << "not an ELF file";
  SimdModule garbage = load_simd_module(SimdLevel::kAvx2, {dir});
  EXPECT_FALSE(garbage.status.usable);
  EXPECT_EQ(garbage.backend, nullptr);
  EXPECT_TRUE(garbage.status.detail.starts_with("module " + (dir / "snee-simd-avx2.so").string() +
                                                " does not load: "))
      << garbage.status.detail;

  // The first directory holding the file decides; the foreign module comes before the real one.
  SimdModule foreign =
      load_simd_module(SimdLevel::kAvx2, {SNEE_TEST_FOREIGN_MODULE_DIR, SNEE_TEST_MODULE_DIR});
  EXPECT_FALSE(foreign.status.usable);
  EXPECT_EQ(foreign.backend, nullptr);
  EXPECT_NE(foreign.status.detail.find("is from another build of snee"), std::string::npos)
      << foreign.status.detail;
  std::filesystem::remove_all(dir);

  for (const SimdLevel level : {SimdLevel::kAvx2, SimdLevel::kAvx512}) {
    if (!simd_module_built(level) || !cpu_runs(level)) continue;
    const SimdModule real = load_simd_module(level, {SNEE_TEST_MODULE_DIR});
    EXPECT_TRUE(real.status.usable) << real.status.detail;
    ASSERT_NE(real.backend, nullptr);
    EXPECT_EQ(real.backend->level, level);
    EXPECT_EQ(real.backend, &simd_backend(level));  // loaded once, whoever asks
  }
}

struct Case {
  const char* scene;
  const char* integrator;
  const char* schedule;
  friend void PrintTo(const Case& c, std::ostream* os) {
    *os << c.scene << " " << c.integrator << " " << c.schedule;
  }
};

class SimdLevels : public ::testing::TestWithParam<Case> {};

// Each usable level against the build's own, bit for bit, with the statistics saying which
// level ran. The scenes cover the path tracer's free flight and transmittance (exp, log1p), the
// HG and GGX samplers (sincos), SNEE's weighing (atan2) on rough and smooth boundaries and the
// AOVs, on every schedule.
TEST_P(SimdLevels, RenderTheSameBytesAsTheBuildsOwnLevel) {
  const Case c = GetParam();
  Scene scene = load_builtin_scene(c.scene).scene;
  scene.camera.width = 32;
  scene.camera.height = 24;
  RenderOptions o;
  o.spp = 8;
  o.seed = 5;
  o.threads = 2;
  o.integrator = c.integrator;
  o.schedule = c.schedule;
  o.aovs.albedo = o.aovs.normal = o.aovs.depth = true;
  o.simd = kCompiledSimdLevel;
  const RenderResult reference = render(scene, o);
  EXPECT_EQ(reference.stats.simd_level, kCompiledSimdLevel);
  for (const SimdLevel level : usable_levels()) {
    o.simd = level;
    const RenderResult r = render(scene, o);
    EXPECT_EQ(r.stats.simd_level, level);
    EXPECT_EQ(r.stats.simd_width, simd_level_lanes(level));
    EXPECT_TRUE(test::bitwise_identical(reference.film, r.film)) << simd_level_name(level);
    EXPECT_EQ(reference.film.albedo, r.film.albedo) << simd_level_name(level);
    EXPECT_EQ(reference.film.depth, r.film.depth) << simd_level_name(level);
    EXPECT_EQ(reference.stats.rays, r.stats.rays) << simd_level_name(level);
    EXPECT_EQ(reference.stats.snee, r.stats.snee) << simd_level_name(level);
    EXPECT_EQ(reference.stats.nonfinite_samples, r.stats.nonfinite_samples);
  }
  // The widest level is the default, the narrowest for the megakernel.
  o.simd.reset();
  EXPECT_EQ(render(scene, o).stats.simd_level,
            std::string(c.schedule) == "megakernel" ? kCompiledSimdLevel : widest_simd_level());
  EXPECT_EQ(default_simd_level("megakernel"), kCompiledSimdLevel);
  EXPECT_EQ(default_simd_level("local"), widest_simd_level());
}

INSTANTIATE_TEST_SUITE_P(Scenes, SimdLevels,
                         ::testing::Values(Case{"default", "pt", "local"},
                                           Case{"default", "snee", "global"},
                                           Case{"sphere-cone-r0.04", "snee", "local"},
                                           Case{"sphere-cone-smooth", "snee", "megakernel"},
                                           Case{"bunny-directional-r0.04", "snee", "local"},
                                           Case{"bunny-env-r0.2", "pt", "global"},
                                           Case{"furnace-sphere", "pt", "local"},
                                           Case{"furnace-sphere-null", "snee", "megakernel"}),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           std::string name = std::string(param.param.scene) + "_" +
                                              param.param.integrator + "_" + param.param.schedule;
                           for (char& ch : name)
                             if (ch == '-' || ch == '.') ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace snee
