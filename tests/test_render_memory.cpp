// render() refuses, before allocating anything, a render whose film, sample buffers and
// workspaces would not fit in RenderOptions::memory_budget.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "scene/scene_loader.h"
#include "scheduler/render.h"

namespace snee {
namespace {

Scene small_scene(int width, int height) {
  Scene scene = load_builtin_scene("bunny-cone-r0.04").scene;
  scene.camera.width = width;
  scene.camera.height = height;
  return scene;
}

RenderOptions options(uint64_t budget) {
  RenderOptions o;
  o.spp = 1;
  o.threads = 2;
  o.memory_budget.bytes = budget;
  return o;
}

// The message of the std::invalid_argument render() throws, or a failure if it renders.
std::string refusal(const Scene& scene, const RenderOptions& o) {
  try {
    render(scene, o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "rendered without an error";
  return "";
}

// 65536^2 pixels died of std::bad_alloc part-way into allocating the film.
TEST(RenderMemory, HugeFilmIsRefusedBeforeAllocating) {
  const std::string message = refusal(small_scene(65536, 65536), options(uint64_t{1} << 30));
  EXPECT_NE(message.find("the film and work buffers of 65536x65536 pixels on 2 threads need "
                         "306.0 GiB, more than the memory budget of 1.0 GiB"),
            std::string::npos)
      << message;
}

// --queue-capacity 1e8 asked for 2.4 KiB of workspace per slot and thread: std::bad_alloc. The
// capacity is now capped (kMaxQueueCapacity), and even the cap's queues are counted first.
TEST(RenderMemory, HugeQueuesAreRefusedBeforeAllocating) {
  RenderOptions o = options(uint64_t{256} << 20);
  o.queue_capacity = kMaxQueueCapacity;
  const std::string message = refusal(small_scene(16, 16), o);
  EXPECT_NE(message.find("more than the memory budget of 256.0 MiB"), std::string::npos) << message;
}

TEST(RenderMemory, SmallRenderFitsASmallBudget) {
  const RenderResult result = render(small_scene(32, 24), options(uint64_t{16} << 20));
  EXPECT_TRUE(result.complete);
  EXPECT_EQ(result.film.mean.size(), 32u * 24u);
}

}  // namespace
}  // namespace snee
