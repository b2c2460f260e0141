// A contact step allocates nothing once its contacts are those of the steps before: global
// operator new counted over steps of the example scenes (boxes, spheres, hulls and a mesh body on
// a table; one and two threads), after steps that let every working array reach its size. Its own
// binary, since it replaces every global operator new and delete (malloc and free underneath).
// The articulated quadruped stands on its feet: its contacts answer through its tree.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/simulation.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, std::align_val_t align) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) { return operator new(size, align); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void* operator new(std::size_t size, std::align_val_t align, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(align);
  return std::aligned_alloc(a, (size + a - 1) / a * a);
}
void* operator new[](std::size_t size, std::align_val_t align, const std::nothrow_t& tag) noexcept {
  return operator new(size, align, tag);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace {

// Allocations over `counted` steps after `settle` steps of the scene on `threads`.
long Allocations(const std::string& name, int threads, int settle, int counted) {
  std::vector<std::string> warnings;
  const scene::Scene s = scene::LoadScene(std::string(MASSPROPS_DATA_DIR) + "/scenes/" + name, warnings);
  scene::Simulation sim = scene::BuildSimulation(s, warnings, threads);
  for (int i = 0; i < settle; ++i) EXPECT_TRUE(sim.physics.Step(s.dt).ok);
  const long before = g_allocations.load();
  for (int i = 0; i < counted; ++i) {
    EXPECT_TRUE(sim.physics.Step(s.dt).ok);
    EXPECT_GT(sim.physics.stats().contacts, 0) << name << ": counted steps with contacts";
  }
  return g_allocations.load() - before;
}

TEST(StepAllocation, ASettledStepAllocatesNothing) {
  EXPECT_EQ(Allocations("box_stack.json", 1, 300, 20), 0);  // ten boxes, resting
  EXPECT_EQ(Allocations("box_stack.json", 2, 300, 20), 0);
  EXPECT_EQ(Allocations("dominoes.json", 1, 300, 20), 0);       // falling: contacts come and go
  EXPECT_EQ(Allocations("spot_on_table.json", 2, 300, 20), 0);  // a mesh body (its field) on a static box
  EXPECT_EQ(Allocations("quadruped.json", 1, 300, 20), 0);      // a jointed robot on its feet
  EXPECT_EQ(Allocations("quadruped.json", 2, 300, 20), 0);
#if !defined(__SANITIZE_ADDRESS__)                      // 2000 steps to settle: the Release run only
  EXPECT_EQ(Allocations("pile.json", 2, 2000, 20), 0);  // 50 boxes and 50 spheres, settled
#endif
}

}  // namespace
