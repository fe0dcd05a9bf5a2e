// Tests for fit/data/order_statistic_tree.h: every order statistic, the
// median and the median absolute deviation against a sort of the same values
// (median_in_place of the deviations, fit/data/median.h), bit for bit, on
// sliding windows and random insertions and removals, with many ties, at the
// window's edges (empty, one, two values) and on large windows.

#include "fit/data/order_statistic_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <random>
#include <utility>
#include <vector>

#include "fit/data/median.h"

namespace gyrotherm::fit {
namespace {

// The tree's answers against the sorted values, for the median and around a few centres.
void expect_matches_sort(const OrderStatisticTree& tree, std::vector<double> values, std::mt19937_64& rng) {
  ASSERT_EQ(tree.size(), values.size());
  std::sort(values.begin(), values.end());
  for (std::size_t k = 0; k < values.size(); ++k) ASSERT_EQ(tree.kth(k), values[k]) << "k " << k;
  std::vector<double> copy = values;
  const double median = median_in_place(copy);
  if (values.empty()) {
    EXPECT_TRUE(std::isnan(tree.median()));
    EXPECT_TRUE(std::isnan(tree.median_abs_deviation(0.0)));
    return;
  }
  ASSERT_EQ(tree.median(), median);
  std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
  for (const double centre : {median, values[pick(rng)], values.front() - 1.5, values.back() + 0.25, 0.0}) {
    std::vector<double> deviations;
    for (const double v : values) deviations.push_back(std::abs(v - centre));
    const double expected = median_in_place(deviations);
    ASSERT_EQ(tree.median_abs_deviation(centre), expected) << "centre " << centre << " n " << values.size();
  }
}

// A value drawn with many ties: a few levels, sometimes a quantised noise, sometimes anything.
double draw(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 3), level(-3, 3);
  std::normal_distribution<double> noise(0.0, 1.0);
  switch (kind(rng)) {
    case 0: return 0.5 * level(rng);
    case 1: return std::round(noise(rng) * 4.0) / 4.0;
    case 2: return -0.0;
    default: return noise(rng) * 1e3;
  }
}

TEST(OrderStatisticTree, EmptyOneAndTwoValues) {
  std::mt19937_64 rng(1);
  OrderStatisticTree tree;
  expect_matches_sort(tree, {}, rng);
  tree.insert(2.5, 7);
  expect_matches_sort(tree, {2.5}, rng);
  EXPECT_EQ(tree.median_abs_deviation(2.5), 0.0);
  tree.insert(-1.0, 8);
  expect_matches_sort(tree, {2.5, -1.0}, rng);
  EXPECT_EQ(tree.median(), 0.75);
  tree.erase(2.5, 7);
  expect_matches_sort(tree, {-1.0}, rng);
  tree.erase(-1.0, 8);
  expect_matches_sort(tree, {}, rng);
  tree.insert(3.0, 9);  // nodes reused after emptying
  expect_matches_sort(tree, {3.0}, rng);
  tree.clear();
  expect_matches_sort(tree, {}, rng);
}

TEST(OrderStatisticTree, EqualValuesLeaveByTheirId) {
  std::mt19937_64 rng(2);
  OrderStatisticTree tree;
  std::vector<double> held;
  for (std::uint64_t id = 0; id < 40; ++id) {
    tree.insert(id % 3 == 0 ? 1.0 : 4.0, id);
    held.push_back(id % 3 == 0 ? 1.0 : 4.0);
  }
  expect_matches_sort(tree, held, rng);
  for (std::uint64_t id = 0; id < 40; id += 2) {  // every other one, equal values among them
    tree.erase(id % 3 == 0 ? 1.0 : 4.0, id);
    held.erase(std::find(held.begin(), held.end(), id % 3 == 0 ? 1.0 : 4.0));
    expect_matches_sort(tree, held, rng);
  }
}

TEST(OrderStatisticTree, SlidingWindowsOfEverySizeMatchASort) {
  std::mt19937_64 rng(3);
  for (const std::size_t width : {1u, 2u, 3u, 4u, 5u, 8u, 31u, 64u}) {
    OrderStatisticTree tree;
    std::deque<std::pair<double, std::uint64_t>> window;
    for (std::uint64_t id = 0; id < 400; ++id) {
      const double x = draw(rng);
      tree.insert(x, id);
      window.emplace_back(x, id);
      if (window.size() > width) {
        tree.erase(window.front().first, window.front().second);
        window.pop_front();
      }
      std::vector<double> values;
      for (const auto& [v, ignored] : window) values.push_back(v);
      expect_matches_sort(tree, values, rng);
    }
  }
}

TEST(OrderStatisticTree, RandomInsertionsAndRemovalsOnALargeWindow) {
  std::mt19937_64 rng(4);
  OrderStatisticTree tree;
  std::vector<std::pair<double, std::uint64_t>> held;
  std::uint64_t next_id = 0;
  std::bernoulli_distribution grow(0.55);
  for (int step = 0; step < 20000; ++step) {
    if (held.empty() || grow(rng)) {
      const double x = draw(rng);
      tree.insert(x, next_id);
      held.emplace_back(x, next_id++);
    } else {
      std::uniform_int_distribution<std::size_t> pick(0, held.size() - 1);
      const std::size_t k = pick(rng);
      tree.erase(held[k].first, held[k].second);
      held[k] = held.back();
      held.pop_back();
    }
    if (step % 997 == 0 || step == 19999) {
      std::vector<double> values;
      for (const auto& [v, ignored] : held) values.push_back(v);
      expect_matches_sort(tree, values, rng);
    }
  }
  EXPECT_GT(held.size(), 1000u);
}

TEST(OrderStatisticTree, SortedInputStaysBalancedEnoughToAnswer) {
  // Values arriving in order (a ramp) would make a plain search tree a list;
  // the treap's priorities do not follow the values. 10^5 of them, then the answers.
  std::mt19937_64 rng(5);
  OrderStatisticTree tree;
  std::vector<double> values;
  for (std::uint64_t id = 0; id < 100000; ++id) {
    tree.insert(static_cast<double>(id) * 0.25, id);
    values.push_back(static_cast<double>(id) * 0.25);
  }
  EXPECT_EQ(tree.median(), 0.5 * (values[49999] + values[50000]));
  std::vector<double> deviations;
  for (const double v : values) deviations.push_back(std::abs(v - 100.0));
  EXPECT_EQ(tree.median_abs_deviation(100.0), median_in_place(deviations));
  for (std::uint64_t id = 0; id < 99990; ++id) tree.erase(static_cast<double>(id) * 0.25, id);
  expect_matches_sort(tree, std::vector<double>(values.end() - 10, values.end()), rng);
}

}  // namespace
}  // namespace gyrotherm::fit
