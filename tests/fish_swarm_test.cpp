// Tests for fit/engines/fish_swarm.h, the moves AFSA and IAFSA share, on the lagged
// cycle problem: every move's geometry (on the segment to the target, no
// farther than Step; a probe within Visual in every coordinate), σ of each
// new point recomputed from the data, prey's two variants, settle keeping the
// better move, refusals once the budget is spent, and the seed.

#include "fit/engines/fish_swarm.h"

#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "lagged_cycle_problem.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing::lagged_cycle;
using fish_swarm::Fish;
using fish_swarm::PreyMove;
using fish_swarm::School;

struct Fixture {
  Cycle cycle = cycle_design(false);
  Eigen::VectorXd y = bias_dph(cycle.design, kPaper, 0.002);
  LinearProblem problem = make_problem(cycle, y);
};

double sigma_of(const LinearProblem& problem, const std::vector<double>& z) {
  return problem.sigma_two_pass(problem.physical(z));
}

TEST(FishSwarm, ScatterPutsEveryFishInTheBoxWithItsSigma) {
  const Fixture d;
  School school(d.problem, 1000, 0.0, 7, 1, PreyMove::jump_to, 1);
  ASSERT_TRUE(school.scatter(12));
  ASSERT_EQ(school.fish().size(), 12u);
  for (const Fish& fish : school.fish()) {
    ASSERT_EQ(fish.x.size(), 3u);
    for (double v : fish.x) {
      EXPECT_GE(v, -1.0);
      EXPECT_LE(v, 1.0);
    }
    EXPECT_NEAR(fish.f, sigma_of(d.problem, fish.x), 1e-9 * fish.f);
  }
  EXPECT_EQ(school.evaluator().evaluations(), 12);
}

TEST(FishSwarm, MoveTowardsStaysOnTheSegmentWithinStep) {
  const Fixture d;
  School school(d.problem, 1000, 0.0, 3, 1, PreyMove::jump_to, 1);
  school.step = 0.2;
  const Fish fish{{0.5, -0.5, 0.1}, 0.0};
  const std::vector<double> target = {-0.3, 0.4, 0.1};
  const double distance = school.distance(fish.x, target);
  for (int k = 0; k < 50; ++k) {
    const std::optional<Fish> next = school.move_towards(fish, target, distance);
    ASSERT_TRUE(next);
    const double moved = school.distance(fish.x, next->x);
    EXPECT_LE(moved, school.step + 1e-12);
    // Collinear: |X_next − X_i| + |target − X_next| = |target − X_i|.
    EXPECT_NEAR(moved + school.distance(next->x, target), distance, 1e-12);
    EXPECT_NEAR(next->f, sigma_of(d.problem, next->x), 1e-9 * next->f);
  }
}

// A fish in a corner far from the optimum: almost every probe is better.
TEST(FishSwarm, PreyJumpsToTheBetterProbeOrStepsTowardsIt) {
  const Fixture d;
  Fish fish{{1.0, 1.0, 1.0}, 0.0};
  fish.f = sigma_of(d.problem, fish.x);
  for (const PreyMove move : {PreyMove::jump_to, PreyMove::step_towards}) {
    School school(d.problem, 100000, 0.0, 11, 1, move, 5);
    school.visual = 0.4;
    school.step = 0.01;
    int better = 0;
    for (int k = 0; k < 200; ++k) {
      const std::optional<Fish> next = school.prey(fish);
      ASSERT_TRUE(next);
      EXPECT_NEAR(next->f, sigma_of(d.problem, next->x), 1e-9 * next->f);
      if (next->f < fish.f) ++better;
      if (move == PreyMove::jump_to) {
        for (std::size_t k2 = 0; k2 < 3; ++k2)
          EXPECT_LE(std::abs(next->x[k2] - fish.x[k2]), school.visual + 1e-12);
      } else {
        EXPECT_LE(school.distance(next->x, fish.x), school.step + 1e-12);
      }
    }
    // The corner is a poor place: with 5 attempts prey nearly always improves.
    EXPECT_GE(better, 190) << (move == PreyMove::jump_to ? "jump_to" : "step_towards");
  }
}

TEST(FishSwarm, SettleKeepsTheBetterMoveAndPreyFillsIn) {
  const Fixture d;
  School school(d.problem, 100000, 0.0, 5, 1, PreyMove::jump_to, 1);
  school.visual = 0.2;
  school.step = 0.05;
  ASSERT_TRUE(school.scatter(2));
  const Fish worse{{0.1, 0.1, 0.1}, 2.0};
  const Fish better{{0.2, 0.2, 0.2}, 1.0};
  ASSERT_TRUE(school.settle(0, worse, better));
  EXPECT_EQ(school.fish()[0].x, better.x);
  ASSERT_TRUE(school.settle(0, better, worse));
  EXPECT_EQ(school.fish()[0].x, better.x);

  // Neither move made: one prey, evaluated, becomes the fish.
  const Fish before = school.fish()[1];
  const long evaluations = school.evaluator().evaluations();
  ASSERT_TRUE(school.settle(1, std::nullopt, std::nullopt));
  EXPECT_GT(school.evaluator().evaluations(), evaluations);
  EXPECT_NE(school.fish()[1].x, before.x);
  EXPECT_NEAR(school.fish()[1].f, sigma_of(d.problem, school.fish()[1].x),
              1e-9 * school.fish()[1].f);

  // One move made, the other by prey: the fish takes the smaller σ of the two.
  const Fish awful{{1.0, -1.0, 1.0}, 1e9};
  ASSERT_TRUE(school.settle(1, awful, std::nullopt));
  EXPECT_LT(school.fish()[1].f, 1e9);
}

TEST(FishSwarm, EveryMoveRefusesOnceTheBudgetIsSpent) {
  const Fixture d;
  School school(d.problem, 5, 0.0, 1, 1, PreyMove::step_towards, 1);
  EXPECT_FALSE(school.scatter(6));  // the sixth fish finds the budget spent
  EXPECT_EQ(school.evaluator().evaluations(), 5);
  const Fish fish = school.fish()[0];
  EXPECT_FALSE(school.prey(fish));
  EXPECT_FALSE(school.move_towards(fish, {0.0, 0.0, 0.0}, school.distance(fish.x, {0, 0, 0})));
  EXPECT_FALSE(school.settle(0, std::nullopt, std::nullopt));
  EXPECT_EQ(school.evaluator().evaluations(), 5);
}

TEST(FishSwarm, TheSeedAndStreamFixTheDraws) {
  const Fixture d;
  const auto scatter = [&](std::uint64_t seed, std::uint64_t stream) {
    School school(d.problem, 100, 0.0, seed, stream, PreyMove::jump_to, 1);
    EXPECT_TRUE(school.scatter(4));
    return school.fish()[3].x;
  };
  EXPECT_EQ(scatter(9, 1), scatter(9, 1));
  EXPECT_NE(scatter(9, 1), scatter(10, 1));
  EXPECT_NE(scatter(9, 1), scatter(9, 2));
}

}  // namespace
}  // namespace gyrotherm::fit
