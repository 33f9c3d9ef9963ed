// StageTimer: nested stages pause the outer one.
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>

#include "test_helpers.h"

#include <cmath>
#include <random>
#include <thread>

using namespace lme_mpm;

TEST(StageTimer, NestedStagesPauseTheOuterOne)
{
  // The inner stage is ten times the outer one's own time, so counting it twice would
  // show whatever the scheduler adds to the sleeps.
  StageTimer timer;
  const unsigned int outer = timer.add("outer"), inner = timer.add("inner");
  {
    StageTimer::Scope a(timer, outer);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    {
      StageTimer::Scope b(timer, inner);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  }
  const auto s = timer.seconds();
  EXPECT_GE(s.at("inner"), 0.200);
  EXPECT_GE(s.at("outer"), 0.020);
  EXPECT_LT(s.at("outer"), 0.200); // the inner stage's time is not counted twice
}
