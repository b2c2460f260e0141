// Isolated work in runs (RunIsolatedInRuns): each child computes several items in turn, and a
// crash, a hang or a throw still ends only the item it happened on, with the outcome a child of
// its own would give; outputs come back whole and in order whatever the number of jobs.

#include "massprops/io/isolation.h"

#include <csignal>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace massprops {
namespace {

bool poisoned = false;  // set in a child by item 3: item 4 crashes only after it, in the same child

std::string Work(std::size_t i) {
  if (i == 3) poisoned = true;
  if (i == 4 && poisoned) std::abort();
  if (i == 11) std::raise(SIGSEGV);
  if (i == 17) std::this_thread::sleep_for(std::chrono::seconds(30));
  if (i == 23) throw std::runtime_error("cannot");
  return std::string(i * 1000, 'x') + std::to_string(i);  // up to 40 KB: several pipe reads
}

TEST(IsolationInRuns, OnlyTheFaultyItemsEndBadly) {
  for (const int jobs : {1, 2, 3}) {
    std::vector<IsolatedOutcome> got;
    std::vector<std::size_t> order;
    RunIsolatedInRuns(40, jobs, 1.0, 8, Work, [&](std::size_t i, IsolatedOutcome&& o) {
      order.push_back(i);
      got.push_back(std::move(o));
    });
    ASSERT_EQ(got.size(), 40u);
    for (std::size_t i = 0; i < 40; ++i) {
      EXPECT_EQ(order[i], i);
      const IsolatedOutcome& o = got[i];
      if (i == 11) {
        EXPECT_EQ(o.end, IsolatedEnd::kCrashed) << jobs;
        EXPECT_TRUE(o.signal == SIGSEGV || o.signal == SIGABRT) << o.signal;  // SIGABRT: AddressSanitizer's report
      } else if (i == 17) {
        EXPECT_EQ(o.end, IsolatedEnd::kTimedOut) << jobs;
        EXPECT_LT(o.seconds, 10.0);
      } else if (i == 23) {
        EXPECT_EQ(o.end, IsolatedEnd::kFailed) << jobs;
      } else {
        // Item 4 crashed after item 3 in the same child; computed again alone, it finishes.
        EXPECT_EQ(o.end, IsolatedEnd::kFinished) << "item " << i << ", jobs " << jobs;
        EXPECT_EQ(o.output, std::string(i * 1000, 'x') + std::to_string(i));
      }
    }
  }
}

// Many runs: more items finished ahead of the first than the parent holds back (a first version
// counted items already delivered as never reported, computed them again and then waited forever).
TEST(IsolationInRuns, ManyRunsEachItemOnce) {
  std::size_t calls = 0;
  RunIsolatedInRuns(
      3000, 2, 5.0, 64, [](std::size_t i) { return std::to_string(i); },
      [&](std::size_t i, IsolatedOutcome&& o) {
        EXPECT_EQ(i, calls++);
        EXPECT_EQ(o.end, IsolatedEnd::kFinished);
        EXPECT_EQ(o.output, std::to_string(i));
      });
  EXPECT_EQ(calls, 3000u);
}

TEST(IsolationInRuns, NoItemsAndOneItem) {
  int calls = 0;
  RunIsolatedInRuns(0, 2, 1.0, 8, Work, [&](std::size_t, IsolatedOutcome&&) { ++calls; });
  EXPECT_EQ(calls, 0);
  RunIsolatedInRuns(1, 2, 1.0, 8, Work, [&](std::size_t i, IsolatedOutcome&& o) {
    ++calls;
    EXPECT_EQ(i, 0u);
    EXPECT_EQ(o.end, IsolatedEnd::kFinished);
    EXPECT_EQ(o.output, "0");
  });
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace massprops
