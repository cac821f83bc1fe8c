// The stage table (kernels/stages/stage_table.h) drives the loop and the scheduler's dispatch:
// every stage runs once per turn, in table order, and only when its input holds something.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "kernels/stages/stage_table.h"
#include "scene/scene_loader.h"
#include "scheduler/render.h"

namespace snee {
namespace {

RenderStats megakernel_stats(const char* integrator) {
  Scene scene = load_scene("builtin:sphere-cone-r0.04").scene;
  scene.camera.width = 12;
  scene.camera.height = 12;
  RenderOptions o;
  o.spp = 2;
  o.threads = 1;
  o.integrator = integrator;
  o.schedule = "megakernel";
  return render(scene, o).stats;
}

uint64_t calls(const RenderStats& s, Stage stage) {
  return s.stage_calls[static_cast<size_t>(stage)];
}

uint64_t rays(const RenderStats& s, RayKind kind) {
  return s.rays[static_cast<size_t>(kind)];
}

// Names and labels are keys and column heads of the reports: two alike would merge two stages.
TEST(StageTable, EveryStageHasItsOwnNameAndLabel) {
  std::set<std::string> names, labels;
  for (const Stage s : kStageLoop) {
    names.insert(stage_name(s));
    labels.insert(stage_label(s));
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(kStageCount));
  EXPECT_EQ(labels.size(), static_cast<size_t>(kStageCount));
  EXPECT_EQ(names.count("?"), 0u);
}

// With one slot every run of a stage holds exactly one path, so the calls the dispatch counts
// are the paths or rays that went through the stage's input: an empty input is never a call.
TEST(StageTable, OneSlotStagesRunOncePerQueuedPath) {
  const RenderStats s = megakernel_stats("snee");
  EXPECT_EQ(calls(s, Stage::kGenerate), s.paths);
  EXPECT_EQ(calls(s, Stage::kRetire), s.paths);
  EXPECT_EQ(calls(s, Stage::kExtend), rays(s, RayKind::kCamera) + rays(s, RayKind::kExtension));
  // A probe stage call queues one probe ray, or none where the probe rate skips the vertex.
  const uint64_t skipped = s.snee[static_cast<int>(SneeCounter::kProbesSkipped)];
  EXPECT_GT(skipped, 0u);
  EXPECT_EQ(calls(s, Stage::kSneeProbe), rays(s, RayKind::kProbe) + skipped);
  EXPECT_GT(calls(s, Stage::kSubdivision), 0u);
  EXPECT_LE(calls(s, Stage::kSubdivision), calls(s, Stage::kSneeProbe));
  EXPECT_LE(calls(s, Stage::kSneeProbe), calls(s, Stage::kMediumEvent));
}

// The path tracer queues no probes, so the SNEE stages are skipped on every turn.
TEST(StageTable, StagesWithNothingQueuedNeverRun) {
  const RenderStats s = megakernel_stats("pt");
  EXPECT_GT(calls(s, Stage::kMediumEvent), 0u);
  EXPECT_EQ(calls(s, Stage::kSneeProbe), 0u);
  EXPECT_EQ(calls(s, Stage::kSubdivision), 0u);
  EXPECT_EQ(rays(s, RayKind::kProbe), 0u);
}

}  // namespace
}  // namespace snee
