// Smoke tests of the measuring commands, `snee bench --quick` and `snee scale`: they run, and
// their JSON holds every documented key. Timings are never asserted (CI machines are noisy).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_directory.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

class PerfCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_test_directory("perf"); }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `snee ARGS` in the temporary directory; returns the exit code, output in output_.
  int snee(const std::string& args) {
    const fs::path log = dir_ / "output.txt";
    const std::string command = "cd '" + dir_.string() + "' && '" SNEE_BINARY "' " + args + " > '" +
                                log.string() + "' 2>&1 < /dev/null";
    const int status = std::system(command.c_str());
    output_ = read(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  std::string read(const fs::path& path) const {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  nlohmann::json json(const std::string& name) const {
    return nlohmann::json::parse(read(dir_ / name));
  }

  fs::path dir_;
  std::string output_;
};

void expect_keys(const nlohmann::json& j, std::initializer_list<const char*> keys,
                 const std::string& where) {
  for (const char* key : keys) EXPECT_TRUE(j.contains(key)) << where << " lacks " << key;
}

TEST_F(PerfCli, BenchQuickWritesEveryKey) {
  ASSERT_EQ(snee("bench --quick --threads 1,2 --json b.json"), 0) << output_;
  EXPECT_NE(output_.find("megakernel"), std::string::npos) << output_;
  const nlohmann::json b = json("b.json");
  expect_keys(
      b,
      {"version", "date", "machine", "settings", "path_state_bytes_per_slot",
       "path_state_bytes_per_slot_snee", "simd_levels", "skipped", "workloads", "memory_vs_spp"},
      "bench");
  EXPECT_GT(b["path_state_bytes_per_slot"].get<int>(), 0);
  // Without --simd each schedule runs at its default level: the megakernel at sse4.2 (the
  // build's own), the wavefront at the widest this machine runs.
  ASSERT_GE(b["simd_levels"].size(), 1u);
  EXPECT_EQ(b["simd_levels"][0], "sse4.2");
  const std::string widest = b["simd_levels"].back();
  // SNEE's vertex memory is allocated only for snee.
  EXPECT_GT(b["path_state_bytes_per_slot_snee"].get<int>(),
            b["path_state_bytes_per_slot"].get<int>());
  ASSERT_GE(b["workloads"].size(), 5u);
  for (const auto& w : b["workloads"]) {
    const std::string name = w["name"];
    expect_keys(w,
                {"description", "scene", "integrator", "triangles", "resolution", "spp",
                 "raw_embree", "runs"},
                name);
    for (const char* q : {"camera_single", "camera_stream", "closest_single", "closest_stream",
                          "occlusion_single", "occlusion_stream"})
      expect_keys(w["raw_embree"]["queries"][q], {"mrays_per_second", "mrays_per_cpu_second"},
                  name + " " + q);
    ASSERT_EQ(w["runs"].size(), 6u) << name;  // 3 schedules x 2 thread counts
    for (const auto& run : w["runs"]) {
      const std::string where = name + " " + run["schedule"].get<std::string>();
      expect_keys(run,
                  {"threads",
                   "seconds",
                   "cpu_seconds",
                   "cpu_share",
                   "repeat_seconds",
                   "paths",
                   "paths_per_second",
                   "paths_per_cpu_second",
                   "rays",
                   "mrays_per_second",
                   "mrays_per_cpu_second",
                   "ratio_to_raw_embree",
                   "vs_megakernel",
                   "stages",
                   "simd_level",
                   "vs_first_simd_level",
                   "queue_capacity",
                   "queue_occupancy",
                   "simd",
                   "path_state_bytes_per_slot",
                   "peak_memory_mib"},
                  where);
      // Every path starts in the batched camera kernel, so lanes ran and some held a slot; a
      // one-slot megakernel unit fills one lane of each batch, except when subdivision weighs
      // one exit's two proposals (TB and BT) in one batch.
      const auto& lanes = run["simd"];
      const std::string level = run["schedule"] == "megakernel" ? "sse4.2" : widest;
      const size_t width = level == "sse4.2" ? 4 : level == "avx2" ? 8 : 16;
      EXPECT_EQ(run["simd_level"], level) << where;
      EXPECT_EQ(lanes["level"], level) << where;
      EXPECT_EQ(lanes["width"].get<size_t>(), width) << where;
      EXPECT_EQ(run["vs_first_simd_level"]["paths_per_cpu_second"], 1.0) << where;
      EXPECT_GT(run["vs_megakernel"]["paths_per_cpu_second"].get<double>(), 0.0) << where;
      const double occupancy = lanes["lane_occupancy"].get<double>();
      EXPECT_GT(occupancy, 0.0) << where;
      EXPECT_LE(occupancy, 1.0) << where;
      if (run["schedule"] == "megakernel") {
        const double one_lane = 1.0 / static_cast<double>(width);
        for (const auto& [kernel, k] : lanes["kernels"].items()) {
          if (k["lanes_run"].get<double>() == 0) continue;  // a stage this workload never ran
          if (kernel == "subdivision_weights") {
            EXPECT_LE(k["occupancy"].get<double>(), 2 * one_lane) << where;
          } else {
            EXPECT_DOUBLE_EQ(k["occupancy"].get<double>(), one_lane) << where << " " << kernel;
          }
        }
      }
      for (const char* kind : {"camera", "extension", "shadow", "probe", "total"})
        EXPECT_TRUE(run["mrays_per_second"].contains(kind)) << where << " " << kind;
      expect_keys(run["stages"]["extend"], {"seconds", "calls", "share_of_thread_time"}, where);
      EXPECT_GT(run["paths"].get<uint64_t>(), 0u) << where;
      EXPECT_GT(run["peak_memory_mib"].get<double>(), 0.0) << where;
    }
  }
  EXPECT_EQ(b["memory_vs_spp"]["runs"].size(), 2u);
}

// --simd all measures every run at every usable level, each against the first (xsimd): the
// speed-up per SIMD width, with the level in the table and the JSON.
TEST_F(PerfCli, BenchMeasuresEveryRunAtEverySimdLevel) {
  ASSERT_EQ(snee("bench --quick --only sphere-pt --threads 1 --simd all --json s.json"), 0)
      << output_;
  const nlohmann::json b = json("s.json");
  ASSERT_GE(b["simd_levels"].size(), 1u);
  EXPECT_EQ(b["simd_levels"][0], "sse4.2");
  const auto& runs = b["workloads"][0]["runs"];
  ASSERT_EQ(runs.size(), 3 * b["simd_levels"].size());  // schedules x levels
  for (const auto& run : runs) {
    const std::string where =
        run["schedule"].get<std::string>() + " " + run["simd_level"].get<std::string>();
    EXPECT_EQ(run["simd"]["level"], run["simd_level"]) << where;
    EXPECT_NE(output_.find(run["simd_level"].get<std::string>()), std::string::npos) << where;
    const double speedup = run["vs_first_simd_level"]["paths_per_cpu_second"].get<double>();
    if (run["simd_level"] == "sse4.2") {
      EXPECT_DOUBLE_EQ(speedup, 1.0) << where;
    } else {
      EXPECT_GT(speedup, 0.0) << where;
    }
  }
  EXPECT_NE(output_.find("xsimd"), std::string::npos) << output_;
}

// A 16x16, 1 spp run samples for milliseconds, far under a second: whatever the machine, the
// figures must say they cannot be trusted, in the JSON and on the terminal. Every stage share
// and the rest are never negative: a rest the sampled stage times overrun is null, with the
// overrun given instead.
TEST_F(PerfCli, ShortBenchRunsCarryTheirWarning) {
  ASSERT_EQ(snee("bench --quick --only sphere-pt --threads 1 --json w.json"), 0) << output_;
  EXPECT_NE(output_.find("under 1 s"), std::string::npos) << output_;
  const nlohmann::json b = json("w.json");
  ASSERT_EQ(b["workloads"].size(), 1u);
  for (const auto& run : b["workloads"][0]["runs"]) {
    const std::string where = run["schedule"];
    ASSERT_TRUE(run.contains("warnings")) << where;
    bool short_run = false;
    for (const auto& warning : run["warnings"])
      short_run |= warning.get<std::string>().find("under 1 s") != std::string::npos;
    EXPECT_TRUE(short_run) << where << " " << run["warnings"].dump();
    const double cpu_share = run["cpu_share"];
    bool cpu_warning = false;
    for (const auto& warning : run["warnings"])
      cpu_warning |=
          warning.get<std::string>().find("of the CPU it asked for") != std::string::npos;
    EXPECT_EQ(cpu_warning, cpu_share < 0.9) << where << " cpu_share " << cpu_share;
    for (const auto& [stage, figures] : run["stages"].items())
      EXPECT_GE(figures["share_of_thread_time"].get<double>(), 0.0) << where << " " << stage;
    const double excess = run["stage_excess_share_of_thread_time"];
    EXPECT_GE(excess, 0.0) << where;
    if (run["other_share_of_thread_time"].is_null()) {
      EXPECT_GT(excess, 0.0) << where;
    } else {
      EXPECT_GE(run["other_share_of_thread_time"].get<double>(), 0.0) << where;
      EXPECT_EQ(excess, 0.0) << where;
    }
  }
}

TEST_F(PerfCli, ShortScaleRunsCarryTheirWarning) {
  ASSERT_EQ(snee("scale builtin:sphere-cone-r0.04 --threads 1 --repeats 1 --resolution 8x8 "
                 "--spp 1 --json w.json"),
            0)
      << output_;
  EXPECT_NE(output_.find("warning: 1 thread(s): ran for"), std::string::npos) << output_;
  const nlohmann::json s = json("w.json");
  ASSERT_EQ(s["results"].size(), 1u);
  const auto& warnings = s["results"][0]["warnings"];
  ASSERT_FALSE(warnings.empty());
  bool short_run = false;
  for (const auto& warning : warnings)
    short_run |= warning.get<std::string>().find("under 1 s") != std::string::npos;
  EXPECT_TRUE(short_run) << warnings.dump();
}

TEST_F(PerfCli, BenchRejectsBadThreadLists) {
  EXPECT_NE(snee("bench --quick --threads 0"), 0) << output_;
  EXPECT_NE(snee("bench --quick --threads 1,,2"), 0) << output_;
}

TEST_F(PerfCli, ScaleWritesJsonAndPlot) {
  ASSERT_EQ(snee("scale builtin:sphere-cone-r0.04 --threads 1,2 --repeats 1 --resolution 16x16 "
                 "--spp 1 --json s.json --plot s.svg"),
            0)
      << output_;
  const nlohmann::json s = json("s.json");
  expect_keys(s,
              {"version", "scene", "integrator", "schedule", "spp", "resolution", "repeats",
               "hardware_threads", "results"},
              "scale");
  ASSERT_EQ(s["results"].size(), 2u);
  for (const auto& r : s["results"]) {
    expect_keys(r,
                {"threads", "seconds", "repeat_seconds", "cpu_seconds", "cpu_share", "paths",
                 "paths_per_second", "mrays_per_second", "speedup", "efficiency", "work_efficiency",
                 "peak_memory_mib"},
                "scale result");
  }
  EXPECT_EQ(s["results"][0]["threads"], 1);
  EXPECT_DOUBLE_EQ(s["results"][0]["speedup"].get<double>(), 1.0);
  const std::string svg = read(dir_ / "s.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u) << svg.substr(0, 80);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("parallel efficiency"), std::string::npos);
  EXPECT_NE(svg.find("ideal"), std::string::npos);
}

}  // namespace
}  // namespace snee
