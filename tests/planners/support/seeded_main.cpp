// The gtest main of the planner test executables: OMPL's global seed is set
// before any test runs, hence before any RNG, sampler or planner exists, so
// that every planner run is the same on every run and every machine (ctest
// runs each test in a process of its own; a whole executable runs its tests
// in a fixed order). Tests that seed again before a planner of their own
// keep doing so.
#include <gtest/gtest.h>
#include <ompl/util/RandomNumbers.h>

int main(int argc, char** argv) {
  ompl::RNG::setSeed(1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
