// The run's record of its time steps against the case's own (src/run/session.hpp, RunStats):
// a run of kTimeStepDropSteps steps below kTimeStepDrop of the case's step is reported once,
// steps shortened to land on an output time are left out, and a step back above ends the run.
#include <gtest/gtest.h>

#include "../../src/run/session.hpp"

using namespace particula;
using particula::run_detail::RunStats;

TEST(TimeStepDrop, ARunOfTenStepsBelowTheThresholdIsReportedOnce) {
  RunStats st;
  const real case_dt = 1e-4, low = 0.5 * kTimeStepDrop * case_dt;
  int reports = 0;
  for (int k = 0; k < 25; ++k) reports += st.add_step(low, false, StepLimit::Acoustic, 100, 1000, case_dt);
  EXPECT_EQ(reports, 1);
  EXPECT_EQ(st.dt_drop_steps, 25);
  EXPECT_EQ(st.dt_drop_reports, 1);
  // a step back above the threshold ends the run of low steps; the next run is reported again
  EXPECT_FALSE(st.add_step(case_dt, false, StepLimit::Acoustic, 100, 1000, case_dt));
  for (int k = 0; k < kTimeStepDropSteps - 1; ++k)
    EXPECT_FALSE(st.add_step(low, false, StepLimit::Acoustic, 100, 1000, case_dt));
  EXPECT_TRUE(st.add_step(low, false, StepLimit::Acoustic, 100, 1000, case_dt));
  EXPECT_EQ(st.dt_drop_reports, 2);
  EXPECT_EQ(st.dt_min, low);
}

TEST(TimeStepDrop, StepsShortenedToLandOnATimeAndStepsAboveTheThresholdDoNotCount) {
  RunStats st;
  const real case_dt = 1e-4;
  for (int k = 0; k < 50; ++k) {
    EXPECT_FALSE(
        st.add_step(1e-9, true, StepLimit::Landing, 100, 1000, case_dt));  // capped: says nothing of the run
    EXPECT_FALSE(st.add_step(1.01 * kTimeStepDrop * case_dt, false, StepLimit::Acoustic, 100, 1000, case_dt));
  }
  EXPECT_EQ(st.dt_drop_steps, 0);
  EXPECT_EQ(st.dt_drop_reports, 0);
  // every step counts in limited_by, the shortened ones under Landing
  EXPECT_EQ(st.limited_by[static_cast<std::size_t>(StepLimit::Landing)], 50);
  EXPECT_EQ(st.limited_by[static_cast<std::size_t>(StepLimit::Acoustic)], 50);
  EXPECT_EQ(st.limited_by[static_cast<std::size_t>(StepLimit::Viscous)], 0);
}
