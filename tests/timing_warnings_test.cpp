// A measurement whose own times cannot be right says so (core/measure/timing_warnings.h): more
// threads slower than one, a shallower depth limit slower than the deepest.

#include <gtest/gtest.h>

#include "core/measure/timing_warnings.h"

namespace {

TEST(TimingWarnings, MoreThreadsSlowerThanOneAreCalledNotThisMachines) {
  const std::string busy = rtiow::thread_scaling_warning(2, 10.0, 8.4);
  EXPECT_NE(busy.find("2 threads traced slower than 1 (0.84x)"), std::string::npos) << busy;
  EXPECT_NE(busy.find("not this machine's"), std::string::npos) << busy;
  EXPECT_EQ(rtiow::thread_scaling_warning(2, 10.0, 19.5), "");
  EXPECT_EQ(rtiow::thread_scaling_warning(2, 10.0, 10.0), "");  // no gain is possible, not wrong
  EXPECT_EQ(rtiow::thread_scaling_warning(1, 10.0, 9.0), "");   // one thread: nothing to scale
}

TEST(TimingWarnings, AShallowerLimitThatTookLongerIsCalledNoise) {
  const std::string noise = rtiow::depth_timing_warning({5, 10, 50}, {0.30, 0.52, 0.50});
  EXPECT_NE(noise.find("depth 10 took longer than depth 50"), std::string::npos) << noise;
  EXPECT_NE(noise.find("noise"), std::string::npos) << noise;
  // Whatever order the sweep lists its limits in.
  EXPECT_NE(rtiow::depth_timing_warning({50, 5}, {0.5, 0.6}), "");
  EXPECT_EQ(rtiow::depth_timing_warning({5, 10, 50}, {0.30, 0.45, 0.50}), "");
  EXPECT_EQ(rtiow::depth_timing_warning({}, {}), "");
}

}  // namespace
