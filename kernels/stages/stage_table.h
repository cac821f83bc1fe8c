// The wavefront stages, declared once (SNEE_STAGES) in the order one turn of a work unit runs
// them. Everything else that lists stages is expanded from this table: the Stage enum and its
// names in the statistics, the order of the loop every schedule runs, and the scheduler's
// dispatch, which skips a stage whose input is empty and times the others
// (scheduler/work_unit.cpp). A stage's contract with the others is stated once, beside its row.
#pragma once

#include <array>
#include <cstddef>

namespace snee {

// X(id, name, label, report, input, run), one row per stage in loop order:
//   id      the Stage enumerator
//   name    its name in the statistics: keys of "stage_seconds" (stats JSON) and of "stages"
//           (bench JSON)
//   label   its short column head in the bench table
//   report  its index in the per-stage statistics arrays, hence its place in every report: the
//           order stages were added in, kept so that reports stay comparable; a new stage takes
//           the next index
//   input   what it consumes, a queue of StageQueues (stages.h); generate's input is the unit's
//           samples not yet started, which the scheduler checks itself (nullptr)
//   run     the kernel (stages.h). Generate and retire are the scheduler's (work_unit.cpp):
//           they hand out and take back a unit's slots, samples and sample buffer
// Each row's comment: the queues it feeds, the path state it reads and writes, the Philox
// purposes it draws (rng.h) and at which event, and what it relies on from the others.
// clang-format off
#define SNEE_STAGES(X)                                                                           \
  /* generate -> extend. Writes a free slot's whole state: pixel, sample, event 0, depth 0,      \
     unit throughput, zero radiance, the camera ray. Draws kCamera at event 0. Runs first so     \
     that slots freed by the last turn's retire trace in this turn. */                           \
  X(kGenerate, "generate", "generate", 0, nullptr, generate)                                     \
  /* extend -> medium | surface | escaped, by the ray's medium and whether it hit. Reads the     \
     ray and medium, writes hit_t, hit_geom and hit_prim. Draws nothing. The only stage that     \
     traces extension rays; a slot waiting here is in no other queue but probe, whose stages     \
     read vertex memory only. */                                                                 \
  X(kExtend, "extend", "extend", 1, &StageQueues::extend, extend)                                \
  /* medium_event -> surface | escaped (flight reached the hit), or extend (scattered), or       \
     retire (depth limit, black, roulette); a scattered slot in a SNEE-eligible (homogeneous)    \
     medium may also go to probe, so it sits in two queues. With grid media it reorders its      \
     own input queue, grid slots last. Queues medium NEE, manifold and guided-exit connections.  \
     Reads ray, hit, medium, throughput; writes throughput, depth, flags, vertex memory,         \
     mis_pdf, the new ray and event + 1 (after its draws). Draws kFreeFlight, kPhase,            \
     kRussianRoulette, kLightSample, kSneeManifold and kSneeGuidedExit* at the event. */         \
  X(kMediumEvent, "medium_event", "medium", 2, &StageQueues::medium, medium_event)               \
  /* snee_probe -> subdivide (the probe found the medium's own boundary from inside). Reads      \
     vertex memory (x_i is the newest vertex, x_j of the memory) and the medium; writes no       \
     path state. Draws kSneeProbe at event - 1: medium_event already advanced the counter. Must  \
     run in the turn of that medium_event, before the slot's next vertex moves the memory on. */ \
  X(kSneeProbe, "snee_probe", "probe", 5, &StageQueues::probe, snee_probe)                       \
  /* subdivision -> shadow connections (top-to-bottom and bottom-to-top place x_j). Reads the    \
     exit points of subdivide, vertex memory and throughput; writes no path state. Draws the     \
     kSneeTopToBottom* and kSneeBottomToTop* blocks at event - 1, the probe's event. */          \
  X(kSubdivision, "subdivision", "subdiv", 6, &StageQueues::subdivide, subdivision)              \
  /* shade_surface -> extend (null crossing or sampled BSDF) or retire; queues NEE and SNEE      \
     exit connections. Reads hit, ray, vertex memory and flags; writes radiance (emission),      \
     throughput, depth, vertex memory, medium, flags, exit memory, guide_ratio, mis_pdf,         \
     eta_scale, the new ray and event + 1. Draws kBsdf, kLightSample, kRussianRoulette at the    \
     event. */                                                                                   \
  X(kShadeSurface, "shade_surface", "surface", 3, &StageQueues::surface, shade_surface)          \
  /* shade_escaped -> retire; an escape after a SNEE exit queues its MIS-weighted connection.    \
     Reads ray, flags, throughput, mis_pdf, exit memory, guide_ratio; writes radiance. Draws     \
     nothing. */                                                                                 \
  X(kShadeEscaped, "shade_escaped", "escaped", 4, &StageQueues::escaped, shade_escaped)          \
  /* shadow_connect -> radiance. Traces every queued connection's segments and adds the clear    \
     ones' values to their slots' radiance, in queue order (the bits depend on it). Runs after   \
     every stage that queues connections and before retire: a slot retired this turn may         \
     still have connections pending, so it sits in retire and in the shadow queue at once. */    \
  X(kShadowConnect, "shadow_connect", "shadow", 7, &StageQueues::shadow, shadow_connect)         \
  /* retire -> the unit's sample buffer; the slot is freed for the next generate. Reads pixel,   \
     sample, radiance (a non-finite sample is dropped and counted). Runs last. */                \
  X(kRetire, "retire", "retire", 8, &StageQueues::retire, retire)
// clang-format on

// Values are the report column (see above), so the per-stage arrays keep their order.
enum class Stage : int {
#define SNEE_STAGE_ENUMERATOR(id, name, label, report, input, run) id = report,
#define SNEE_STAGE_ONE(id, name, label, report, input, run) +1
  SNEE_STAGES(SNEE_STAGE_ENUMERATOR) kCount = 0 SNEE_STAGES(SNEE_STAGE_ONE)
#undef SNEE_STAGE_ONE
#undef SNEE_STAGE_ENUMERATOR
};
inline constexpr int kStageCount = static_cast<int>(Stage::kCount);

// One turn of the stage loop, in order: the loop of every schedule.
inline constexpr std::array<Stage, kStageCount> kStageLoop = {
#define SNEE_STAGE_IN_LOOP(id, name, label, report, input, run) Stage::id,
    SNEE_STAGES(SNEE_STAGE_IN_LOOP)
#undef SNEE_STAGE_IN_LOOP
};

// The report column numbers the stages 0 .. kStageCount - 1, each once.
constexpr bool stage_reports_are_a_permutation() {
  std::array<int, kStageCount> seen{};
  for (const Stage s : kStageLoop) {
    const int i = static_cast<int>(s);
    if (i < 0 || i >= kStageCount || seen[static_cast<size_t>(i)]++ > 0) return false;
  }
  return true;
}
static_assert(stage_reports_are_a_permutation(), "SNEE_STAGES: report indices must be 0..n-1");

struct StageNames {
  const char* name;   // in the statistics
  const char* label;  // in the bench table
};

constexpr StageNames stage_names(Stage s) {
  switch (s) {
#define SNEE_STAGE_NAMES(id, name, label, report, input, run) \
  case Stage::id:                                             \
    return {name, label};
    SNEE_STAGES(SNEE_STAGE_NAMES)
#undef SNEE_STAGE_NAMES
    case Stage::kCount:
      break;
  }
  return {"?", "?"};
}
constexpr const char* stage_name(Stage s) {
  return stage_names(s).name;
}
constexpr const char* stage_label(Stage s) {
  return stage_names(s).label;
}

}  // namespace snee
