// The snee binary as a user meets it: help, version and SIMD levels, usage errors, scene
// errors, a tiny render whose outputs are read back, and what the statistics and warnings say.
// Writing the outputs safely (checkpoints, signals, failed writes) is test_cli_outputs.cpp.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/stats_json.h"
#include "scene/film.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"
#include "scheduler/simd_dispatch.h"
#include "tests/support/cli_fixture.h"
#include "tests/support/command_line.h"

namespace snee {
namespace {

namespace fs = std::filesystem;
using test::CliTest;
using test::contains;
using test::Outcome;
using test::read_text_file;
using test::write_file;

TEST_F(CliTest, RenderHelpListsEveryOption) {
  const Outcome run = snee("render --help");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  for (const char* option :
       {"SCENE", "builtin:", "--spp", "--threads", "--seed", "--integrator", "-o", "--output",
        "--stats", "--resolution", "--max-depth", "--queue-capacity", "--tile-size",
        "--samples-per-unit", "--schedule", "--checkpoint", "--quiet", "--simd"})
    EXPECT_TRUE(contains(run.output, option)) << option << " missing from:\n" << run.output;
}

TEST_F(CliTest, TopLevelHelpAndVersion) {
  const Outcome help = snee("--help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_TRUE(contains(help.output, "render")) << help.output;
  EXPECT_TRUE(contains(help.output, "scenes")) << help.output;
  EXPECT_EQ(snee("scenes --help").exit_code, 0);

  const Outcome version = snee("--version");
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_TRUE(contains(version.output, SNEE_VERSION)) << version.output;
  // The level that renders by default, and every level's standing here.
  EXPECT_TRUE(contains(version.output, "SIMD: " + simd_level_description(widest_simd_level()) +
                                           ", the widest this machine runs"))
      << version.output;
  for (const SimdLevelStatus& s : simd_levels()) {
    EXPECT_TRUE(contains(version.output, std::string(simd_level_name(s.level)) + " "))
        << version.output;
    EXPECT_TRUE(contains(version.output, s.detail)) << version.output;
  }
}

// --simd forces a level: the run says which one rendered (console, stats JSON, EXR metadata),
// and the pixels are the same at every level this machine can use.
TEST_F(CliTest, SimdOptionForcesALevelThatRendersTheSamePixels) {
  std::vector<float> first;
  for (const SimdLevelStatus& s : simd_levels()) {
    if (!s.usable) continue;
    const std::string name(simd_level_name(s.level));
    const Outcome run = snee(
        "render builtin:sphere-cone-r0.04 --integrator snee --spp 2 "
        "--resolution 16x12 -o " +
        name + ".exr --stats " + name + ".json --simd " + name);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "Mrays/s, " + name + "\n")) << run.output;
    const auto stats = nlohmann::json::parse(read_text_file(dir_ / (name + ".json")));
    EXPECT_EQ(stats["simd"]["level"], name);
    EXPECT_EQ(stats["simd"]["width"], simd_level_lanes(s.level));
    auto in = OIIO::ImageInput::open(path(name + ".exr"));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("snee:simd"),
              simd_level_description(s.level) + ", forced by --simd");
    const Film film = read_exr(path(name + ".exr"));
    std::vector<float> pixels;
    for (const Rgb& p : film.mean) pixels.insert(pixels.end(), {p.x, p.y, p.z});
    if (first.empty()) {
      first = pixels;
    } else {
      EXPECT_EQ(std::memcmp(first.data(), pixels.data(), first.size() * sizeof(float)), 0) << name;
    }
  }
  EXPECT_FALSE(first.empty());
}

// `cmake --install` puts the program in PREFIX/bin and the SIMD modules in PREFIX/lib/snee,
// where the installed program finds them before the build tree's.
TEST_F(CliTest, AnInstalledSneeLoadsTheModulesInstalledWithIt) {
  const fs::path prefix = dir_ / "prefix";
  ASSERT_EQ(test::run_command(
                std::string("'" SNEE_CMAKE_COMMAND "' --install '" SNEE_BUILD_DIR "' --prefix '") +
                    prefix.string() + "'",
                dir_ / "install.txt"),
            0)
      << read_text_file(dir_ / "install.txt");
  const std::string installed = (prefix / "bin" / "snee").string();
  std::string version, output;
  ASSERT_EQ(test::run_in_directory(dir_, installed, "--version", version), 0) << version;
  for (const SimdLevelStatus& s : simd_levels()) {
    if (!s.usable || s.level == kCompiledSimdLevel) continue;
    const std::string module = "snee-simd-" + std::string(simd_level_name(s.level)) + ".so";
    EXPECT_TRUE(contains(version, "usable: module " + (prefix / "lib" / "snee" / module).string()))
        << version;
    ASSERT_EQ(test::run_in_directory(dir_, installed,
                                     "render builtin:furnace-sphere --spp 1 --resolution 8x8 -o "
                                     "i.exr --simd " +
                                         std::string(simd_level_name(s.level)),
                                     output),
              0)
        << output;
    EXPECT_TRUE(contains(output, std::string(simd_level_name(s.level)) + "\n")) << output;
  }
}

TEST_F(CliTest, AnUnknownSimdLevelIsAUsageError) {
  const Outcome run = snee("render builtin:default --spp 1 --simd avx");
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "the SIMD level must be sse4.2, avx2 or avx512: avx"))
      << run.output;
  const Outcome bench = snee("bench --quick --simd sse4.2,neon");
  EXPECT_NE(bench.exit_code, 0) << bench.output;
  EXPECT_TRUE(contains(bench.output, "not 'neon'")) << bench.output;
}

TEST_F(CliTest, NoSubcommandIsAnError) {
  const Outcome run = snee("");
  EXPECT_NE(run.exit_code, 0) << run.output;
}

TEST_F(CliTest, UnknownOptionIsAnError) {
  const Outcome run = snee("render --bogus-option 3");
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "--bogus-option")) << run.output;
}

TEST_F(CliTest, BadValuesAreErrors) {
  for (const char* args :
       {"render --resolution 0x5", "render --resolution 16", "render --resolution 16x-2",
        "render --spp 0", "render --spp many", "render --threads -1", "render --integrator bdpt",
        "render -o image.tif", "render --tile-size 0"}) {
    const Outcome run = snee(args);
    EXPECT_NE(run.exit_code, 0) << args << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, "error")) << args << "\n" << run.output;
  }
}

TEST_F(CliTest, MissingSceneFileNamesThePath) {
  const std::string scene = path("no_such_scene.json");
  const Outcome run = snee("render '" + scene + "' --quiet");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, scene)) << run.output;
}

TEST_F(CliTest, MalformedJsonNamesFileAndLine) {
  const std::string scene = path("broken.json");
  write_file(scene, "{\n  \"camera\": {\n    \"fov\": 40,,\n  }\n}\n");
  const Outcome run = snee("render '" + scene + "' --quiet");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, scene)) << run.output;
  EXPECT_TRUE(contains(run.output, scene + ":3:15: malformed JSON")) << run.output;
}

TEST_F(CliTest, UnknownKeyNamesTheJsonPath) {
  const std::string scene = path("typo.json");
  write_file(scene, R"({"camera": {"fov": 40, "bogus_key": 1}})");
  const Outcome run = snee("render '" + scene + "' --quiet");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "camera.bogus_key")) << run.output;
}

TEST_F(CliTest, ScenesListsTheDefaultScene) {
  const Outcome run = snee("scenes");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "default")) << run.output;
  EXPECT_TRUE(contains(run.output, "furnace-sphere")) << run.output;
}

TEST_F(CliTest, TinyRenderWritesExrPngAndStats) {
  const Outcome run = snee(
      "render builtin:furnace-sphere --resolution 16x16 --spp 2 -o out/a.exr --stats s.json "
      "--quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "wrote out/a.exr")) << run.output;
  EXPECT_TRUE(contains(run.output, "wrote out/a.png")) << run.output;

  const Film film = read_exr(path("out/a.exr"));
  EXPECT_EQ(film.width, 16);
  EXPECT_EQ(film.height, 16);
  EXPECT_EQ(film.variance_of_mean.size(), 256u);
  EXPECT_EQ(film.meta.spp, 2);
  EXPECT_TRUE(fs::is_regular_file(path("out/a.png")));

  const auto stats = nlohmann::json::parse(read_text_file(path("s.json")));
  for (const char* key :
       {"version", "scene", "integrator", "spp", "complete", "min_spp", "seed", "threads",
        "resolution", "seconds", "stage_seconds", "rays", "paths", "mrays_per_second",
        "path_state_bytes_per_slot", "schedule", "queue_occupancy", "simd"})
    EXPECT_TRUE(stats.contains(key)) << key;
  // The camera kernel started every path: 16 x 16 x 2 active lanes, in whole batches.
  const auto& camera_lanes = stats["simd"]["kernels"]["generate"];
  EXPECT_EQ(camera_lanes["active_lanes"].get<uint64_t>(), 16u * 16u * 2u);
  EXPECT_EQ(camera_lanes["lanes_run"].get<uint64_t>() % stats["simd"]["width"].get<uint64_t>(), 0u);
  EXPECT_TRUE(stats["simd"]["kernels"].contains("medium_event"));
  EXPECT_EQ(stats["spp"], 2);
  EXPECT_EQ(stats["complete"], true);
  EXPECT_EQ(stats["min_spp"], 2);
  EXPECT_EQ(stats["resolution"]["width"], 16);
  EXPECT_EQ(stats["resolution"]["height"], 16);
  for (const char* kind : {"camera", "extension", "shadow", "probe", "total"})
    EXPECT_TRUE(stats["rays"].contains(kind)) << kind;
  EXPECT_GE(stats["rays"]["camera"].get<uint64_t>(), 16u * 16u * 2u);
}

TEST_F(CliTest, NonFiniteNumbersAreRejected) {
  for (const char* option :
       {"render --snee-distance-mix", "render --snee-joint-mix", "render --snee-light-limit",
        "render --checkpoint", "compare --time"}) {
    for (const char* value : {"nan", "inf", "-inf"}) {
      const std::string args = std::string(option) + " " + value + " --resolution 4x4";
      const Outcome run = snee(args);
      EXPECT_NE(run.exit_code, 0) << args << "\n" << run.output;
      EXPECT_TRUE(contains(run.output, "expected a finite number")) << args << "\n" << run.output;
      EXPECT_FALSE(fs::exists(path("out"))) << args << ": rendered anyway";
    }
  }
}

// The command line accepts exactly what render() does (scheduler/render.h).
TEST_F(CliTest, QueueCapacityLimitsAreRendersLimits) {
  for (const char* capacity : {"15", "65537", "100000000"}) {
    const Outcome run = snee(std::string("render --queue-capacity ") + capacity);
    EXPECT_NE(run.exit_code, 0) << capacity << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, "expected an integer from 16 to 65536")) << run.output;
  }
  for (const char* capacity : {"16", "65536"}) {
    const Outcome run = snee(std::string("render builtin:furnace-sphere --resolution 8x8 --spp 1 "
                                         "--quiet --queue-capacity ") +
                             capacity);
    EXPECT_EQ(run.exit_code, 0) << capacity << "\n" << run.output;
  }
}

// A tile beyond the largest image and more sample indices per unit than kMaxSamplesPerUnit
// used to pass the command line (render() took any positive value).
TEST_F(CliTest, TileSizeAndSamplesPerUnitLimitsAreRendersLimits) {
  for (const char* tile : {"0", "32769", "2147483647"}) {
    const Outcome run = snee(std::string("render --tile-size ") + tile);
    EXPECT_NE(run.exit_code, 0) << tile << "\n" << run.output;
    EXPECT_TRUE(contains(run.output, "--tile-size: expected an integer from 1 to 32768, got '" +
                                         std::string(tile) + "'"))
        << run.output;
  }
  for (const char* command : {"render", "bench"}) {
    for (const char* samples : {"0", "65537"}) {
      const Outcome run = snee(std::string(command) + " --samples-per-unit " + samples);
      EXPECT_NE(run.exit_code, 0) << command << " " << samples << "\n" << run.output;
      EXPECT_TRUE(contains(run.output,
                           "--samples-per-unit: expected an integer from 1 to 65536, "
                           "got '" +
                               std::string(samples) + "'"))
          << run.output;
    }
  }
  const Outcome run = snee(
      "render builtin:furnace-sphere --resolution 8x8 --spp 2 --quiet --tile-size 32768 "
      "--samples-per-unit 65536");
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

// A radiance near the top of float's range is valid, yet its paths overflow to infinity:
// the count of such samples reaches the statistics, stderr and the EXR.
// A light brighter than kMaxBrightness only ever produced non-finite samples, so the loader
// refuses it. The renderer, given one anyway (a Scene built in code), counts its non-finite
// samples, and every report carries the count: RenderStats, the EXR metadata after a write and
// read, --stats and the warning the CLI prints at the end.
TEST_F(CliTest, NonFiniteSamplesAreReported) {
  const std::string bright = R"({
    "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40, "resolution": [16, 16]},
    "lights": [{"type": "constant", "radiance": 3e38}],
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                "material": {"type": "diffuse", "albedo": 0.5}}]})";
  write_file(path("bright.json"), bright);
  const Outcome refused = snee("render bright.json --spp 4 --quiet -o b.exr");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_TRUE(contains(refused.output, "bright.json: lights[0].radiance")) << refused.output;
  EXPECT_TRUE(contains(refused.output, "1e+30")) << refused.output;

  nlohmann::json doc = nlohmann::json::parse(bright);
  doc["lights"][0]["radiance"] = 1.0;
  Scene scene = load_scene_json(doc, "bright", ".").scene;
  scene.lights[0].radiance = Rgb(3e38f);
  RenderOptions options;
  options.spp = 4;
  const RenderResult result = render(scene, options);
  const uint64_t nonfinite = result.stats.nonfinite_samples;
  EXPECT_GT(nonfinite, 0u);
  EXPECT_EQ(result.film.meta.nonfinite_samples, nonfinite);
  write_exr(result.film, path("b.exr"));
  EXPECT_EQ(read_exr(path("b.exr")).meta.nonfinite_samples, nonfinite);
  EXPECT_EQ(stats_json("bright", options, result)["nonfinite_samples"], nonfinite);
  EXPECT_TRUE(contains(nonfinite_warning(result.stats),
                       "warning: " + std::to_string(nonfinite) + " of 1024 samples"))
      << nonfinite_warning(result.stats);

  const Outcome clean = snee(
      "render builtin:furnace-sphere --resolution 8x8 --spp 1 --quiet "
      "-o f.exr --stats f.json");
  ASSERT_EQ(clean.exit_code, 0) << clean.output;
  EXPECT_FALSE(contains(clean.output, "not finite")) << clean.output;
  EXPECT_EQ(nlohmann::json::parse(read_text_file(path("f.json")))["nonfinite_samples"], 0);
}

// A medium whose mean free path is within 100 ray clearances of this scene's float precision
// renders too dark near its boundary (docs/reliability.md): the render says so on stderr, before
// rendering, and in --stats, naming the medium; a medium 1000 times thinner is not warned about.
TEST_F(CliTest, AMeanFreePathNearTheRayClearanceIsWarnedAbout) {
  const auto scene = [](const char* sigma_s) {
    return std::string(R"({
    "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40, "resolution": [8, 8]},
    "lights": [{"type": "constant", "radiance": 1}],
    "materials": [{"name": "glass", "type": "dielectric", "ior": 1.5}],
    "media": [{"name": "chalk", "sigma_s": )") +
           sigma_s + R"(, "sigma_a": 0}],
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass",
                "medium": "chalk"}]})";
  };
  write_file(path("dense.json"), scene("1e6"));
  const Outcome dense =
      snee("render dense.json --spp 1 --max-depth 64 --quiet -o d.exr --stats d.json");
  ASSERT_EQ(dense.exit_code, 0) << dense.output;
  EXPECT_TRUE(contains(dense.output, "warning: the mean free path of medium 'chalk' is only"))
      << dense.output;
  const double clearances =
      nlohmann::json::parse(read_text_file(path("d.json")))["shortest_free_path_clearances"];
  EXPECT_GT(clearances, 0.5);
  EXPECT_LT(clearances, 2.0);  // 1e-6 against 4 float epsilons of a scene of extent 2
  // Given before rendering: a render refused before its first sample still warns.
  const Outcome refused =
      snee("render dense.json --spp 1 --resolution 4000x4000 --max-memory 40M --quiet -o r.exr");
  EXPECT_NE(refused.exit_code, 0) << refused.output;
  EXPECT_TRUE(contains(refused.output, "memory budget")) << refused.output;
  EXPECT_TRUE(contains(refused.output, "warning: the mean free path of medium 'chalk' is only"))
      << refused.output;

  write_file(path("thin.json"), scene("1e3"));
  const Outcome thin =
      snee("render thin.json --spp 1 --max-depth 64 --quiet -o t.exr --stats t.json");
  ASSERT_EQ(thin.exit_code, 0) << thin.output;
  EXPECT_FALSE(contains(thin.output, "mean free path")) << thin.output;
  EXPECT_GT(nlohmann::json::parse(read_text_file(path("t.json")))["shortest_free_path_clearances"],
            100.0);
}

// Under only wide lights snee says that it ran as pt, and --stats records it; the limit option
// brings SNEE back and is checked like every number on the command line.
TEST_F(CliTest, SneeSaysWhenItRanAsThePathTracer) {
  const std::string render =
      "render builtin:furnace-sphere --resolution 8x8 --spp 1 --quiet "
      "--integrator snee -o f.exr --stats f.json";
  const Outcome off = snee(render);
  ASSERT_EQ(off.exit_code, 0) << off.output;
  EXPECT_TRUE(contains(off.output,
                       "note: snee ran as pt: the smallest light fills a cone of "
                       "180 degrees, more than --snee-light-limit 15"))
      << off.output;
  const nlohmann::json stats = nlohmann::json::parse(read_text_file(path("f.json")));
  EXPECT_EQ(stats["snee"]["engaged"], false);
  EXPECT_EQ(stats["snee"]["smallest_light_half_angle_degrees"], 180.0);
  EXPECT_EQ(stats["snee_options"]["light_limit_degrees"], 15.0);
  EXPECT_EQ(stats["rays"]["probe"], 0);

  const Outcome on = snee(render + " --snee-light-limit 180");
  ASSERT_EQ(on.exit_code, 0) << on.output;
  EXPECT_FALSE(contains(on.output, "ran as pt")) << on.output;
  EXPECT_EQ(nlohmann::json::parse(read_text_file(path("f.json")))["snee"]["engaged"], true);

  for (const char* bad : {"nan", "-1", "181"}) {
    const Outcome refused = snee(render + " --snee-light-limit " + bad);
    EXPECT_NE(refused.exit_code, 0) << bad << ": " << refused.output;
    EXPECT_TRUE(contains(refused.output, "--snee-light-limit")) << refused.output;
  }
}

// The chain levels behind a mesh reach the stats JSON, and a count outside 1-8 is refused
// naming the option.
TEST_F(CliTest, ChainLevelsAreRecordedAndChecked) {
  const std::string render =
      "render builtin:bunny-directional-smooth --resolution 8x8 --spp 1 --quiet "
      "--integrator snee -o b.exr --stats b.json --snee-chain-levels ";
  const Outcome two = snee(render + "2");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_EQ(
      nlohmann::json::parse(read_text_file(path("b.json")))["snee_options"]["mesh_chain_levels"],
      2);
  for (const char* bad : {"0", "9", "-1", "two"}) {
    const Outcome refused = snee(render + bad);
    EXPECT_NE(refused.exit_code, 0) << bad << ": " << refused.output;
    EXPECT_TRUE(contains(refused.output, "--snee-chain-levels")) << refused.output;
  }
}

// A grid medium renders from the command line; snee says it samples it as pt does; a broken
// .vol file stops the render with the file, the JSON path and what was wrong.
TEST_F(CliTest, GridMediumRendersAndABadGridFileIsNamed) {
  const auto scene_with = [](const std::string& density) {
    return R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0]},
      "materials": [{"name": "glass", "type": "dielectric", "ior": 1.5}],
      "media": [{"name": "smoke", "type": "grid", "sigma_s": 2, "density": )" +
           density + R"(}],
      "shapes": [{"type": "sphere", "material": "glass", "medium": "smoke"}],
      "lights": [{"type": "cone", "direction": [0, 1, 1], "half_angle_degrees": 5,
                  "radiance": 100}]})";
  };
  write_file(path("grid.json"), scene_with(R"({"resolution": [2, 1, 1], "values": [0.5, 2],
                            "bounds": {"min": [-1, -1, -1], "max": [1, 1, 1]}})"));
  const Outcome ok =
      snee("render grid.json --resolution 8x8 --spp 2 --quiet --integrator snee -o g.exr");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_TRUE(contains(ok.output, "note: snee samples the grid media 'smoke' as pt does"))
      << ok.output;
  EXPECT_TRUE(fs::is_regular_file(path("g.exr")));

  write_file(path("smoke.vol"), "VOX\x03 and not a grid at all, but long enough for a header");
  write_file(path("bad.json"), scene_with(R"({"file": "smoke.vol"})"));
  const Outcome bad = snee("render bad.json --resolution 8x8 --spp 2 --quiet -o b.exr");
  EXPECT_NE(bad.exit_code, 0) << bad.output;
  EXPECT_TRUE(contains(bad.output, "media[0].density.file")) << bad.output;
  EXPECT_TRUE(contains(bad.output, "smoke.vol: does not start with 'VOL'")) << bad.output;
  EXPECT_FALSE(fs::exists(path("b.exr")));
}

TEST_F(CliTest, DefaultOutputIsNamedAfterTheScene) {
  const Outcome run = snee("render builtin:furnace-sphere --resolution 8x4 --spp 1 --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::is_regular_file(path("out/furnace-sphere.exr"))) << run.output;
  EXPECT_TRUE(fs::is_regular_file(path("out/furnace-sphere.png"))) << run.output;
  EXPECT_EQ(read_exr(path("out/furnace-sphere.exr")).width, 8);
}

TEST_F(CliTest, SneeStatsCountProbesAndConnections) {
  const Outcome run = snee(
      "render builtin:sphere-cone-r0.2 --integrator snee --resolution 16x16 --spp 2 --quiet "
      "--snee-strategies tb,ub,ul -o out/s.exr --stats s.json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto stats = nlohmann::json::parse(read_text_file(path("s.json")));
  EXPECT_EQ(stats["snee_options"]["strategies"], "tb,ub,ul");
  EXPECT_EQ(stats["snee_options"]["probe"], "uniform");
  const auto& c = stats["snee"];
  EXPECT_GT(c["probes"].get<uint64_t>(), 0u);
  EXPECT_EQ(c["probes"], stats["rays"]["probe"]);
  EXPECT_GT(c["top_to_bottom_connections"].get<uint64_t>(), 0u);
  EXPECT_EQ(c["bottom_to_top_connections"], 0) << "bt was not enabled";
  EXPECT_EQ(c["connection_rays"].get<uint64_t>(),
            3 * c["top_to_bottom_connections"].get<uint64_t>());
  EXPECT_EQ(snee("render builtin:sphere-cone-r0.2 --snee-strategies tb,xy").exit_code == 0, false);
}

TEST_F(CliTest, CompareWritesReportSheetAndRenders) {
  const Outcome run = snee(
      "compare builtin:sphere-cone-r0.2 --resolution 12x12 --spp 2 --reference-spp 4 -o cmp "
      "--quiet");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* file : {"cmp/pt.exr", "cmp/snee.exr", "cmp/reference.exr", "cmp/compare.json",
                           "cmp/contact-sheet.png"})
    EXPECT_TRUE(fs::is_regular_file(path(file))) << file;
  const auto report = nlohmann::json::parse(read_text_file(path("cmp/compare.json")));
  EXPECT_EQ(report["mode"], "equal-spp");
  ASSERT_EQ(report["integrators"].size(), 2u);
  EXPECT_EQ(report["integrators"][0]["name"], "pt");
  EXPECT_EQ(report["integrators"][0]["efficiency_vs_first"], 1.0);
  for (const auto& entry : report["integrators"]) {
    EXPECT_EQ(entry["spp"], 2);
    EXPECT_GT(entry["relative_mse_raw"].get<double>(), 0.0);
  }
  // A reference of another size is an error, not a silently wrong report.
  const Outcome mismatch =
      snee("compare builtin:sphere-cone-r0.2 --resolution 8x8 --spp 1 --reference cmp/pt.exr");
  EXPECT_NE(mismatch.exit_code, 0);
  EXPECT_TRUE(contains(mismatch.output, "reference is 12x12")) << mismatch.output;
}

}  // namespace
}  // namespace snee
