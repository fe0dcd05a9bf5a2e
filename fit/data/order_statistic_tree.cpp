// The order-statistic treap (fit/data/order_statistic_tree.h).
#include "fit/data/order_statistic_tree.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace gyrotherm::fit {
namespace {

// SplitMix64's finaliser (Steele, Lea, Flood, OOPSLA 2014): distinct ids give
// priorities that look independent, so the tree's shape does not follow the
// order the values come in.
std::uint64_t priority_of(std::uint64_t id) {
  std::uint64_t z = id + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

void OrderStatisticTree::insert(double x, std::uint64_t id) {
  assert(!std::isnan(x));
  std::int32_t n = 0;
  if (!free_.empty()) {
    n = free_.back();
    free_.pop_back();
  } else {
    n = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
  }
  at(n) = Node{x, id, priority_of(id), -1, -1, 1};
  root_ = insert_at(root_, n);
}

void OrderStatisticTree::erase(double x, std::uint64_t id) { root_ = erase_at(root_, x, id); }

void OrderStatisticTree::clear() {
  nodes_.clear();
  free_.clear();
  root_ = -1;
}

std::int32_t OrderStatisticTree::insert_at(std::int32_t t, std::int32_t n) {
  if (t < 0) return n;
  if (at(n).priority > at(t).priority) {
    split(t, at(n).x, at(n).id, at(n).left, at(n).right);
    update(n);
    return n;
  }
  if (before(at(n).x, at(n).id, t)) {
    const std::int32_t left = insert_at(at(t).left, n);
    at(t).left = left;
  } else {
    const std::int32_t right = insert_at(at(t).right, n);
    at(t).right = right;
  }
  ++at(t).size;
  return t;
}

std::int32_t OrderStatisticTree::erase_at(std::int32_t t, double x, std::uint64_t id) {
  assert(t >= 0);  // (x, id) is in the tree
  if (at(t).id == id && !(at(t).x < x) && !(x < at(t).x)) {
    const std::int32_t joined = merge(at(t).left, at(t).right);
    free_.push_back(t);
    return joined;
  }
  if (before(x, id, t)) {
    const std::int32_t left = erase_at(at(t).left, x, id);
    at(t).left = left;
  } else {
    const std::int32_t right = erase_at(at(t).right, x, id);
    at(t).right = right;
  }
  --at(t).size;
  return t;
}

void OrderStatisticTree::split(std::int32_t t, double x, std::uint64_t id, std::int32_t& before_part,
                               std::int32_t& after_part) {
  if (t < 0) {
    before_part = after_part = -1;
    return;
  }
  if (before(x, id, t)) {  // t and its right subtree come after (x, id)
    split(at(t).left, x, id, before_part, at(t).left);
    after_part = t;
  } else {
    split(at(t).right, x, id, at(t).right, after_part);
    before_part = t;
  }
  update(t);
}

std::int32_t OrderStatisticTree::merge(std::int32_t a, std::int32_t b) {
  if (a < 0) return b;
  if (b < 0) return a;
  if (at(a).priority > at(b).priority) {
    const std::int32_t right = merge(at(a).right, b);
    at(a).right = right;
    update(a);
    return a;
  }
  const std::int32_t left = merge(a, at(b).left);
  at(b).left = left;
  update(b);
  return b;
}

double OrderStatisticTree::kth(std::size_t k) const {
  assert(k < size());
  std::int32_t t = root_;
  for (;;) {
    const std::size_t left = size_of(at(t).left);
    if (k < left) {
      t = at(t).left;
    } else if (k == left) {
      return at(t).x;
    } else {
      k -= left + 1;
      t = at(t).right;
    }
  }
}

double OrderStatisticTree::median() const {
  const std::size_t n = size();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  return n % 2 == 1 ? kth(n / 2) : 0.5 * (kth(n / 2 - 1) + kth(n / 2));
}

double OrderStatisticTree::median_abs_deviation(double m) const {
  const std::size_t n = size();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  // below: the values at or under m, a_{b-1} ≥ … ≥ a_0, as |a − m| rising; above: a_b, a_{b+1}, … rising.
  std::size_t below = 0;  // how many values are ≤ m
  for (std::size_t hi = n; below < hi;) {
    const std::size_t mid = below + (hi - below) / 2;
    if (kth(mid) <= m) below = mid + 1;
    else hi = mid;
  }
  const std::size_t above = n - below;
  const auto low = [&](std::size_t j) { return std::abs(kth(below - 1 - j) - m); };
  const auto high = [&](std::size_t j) { return std::abs(kth(below + j) - m); };
  // The k-th smallest (from 0) of the two rising sequences: i from the first,
  // k + 1 − i from the second, i the least with high(k − i) ≥ low(i) (or none left).
  const auto select = [&](std::size_t k) {
    std::size_t lo = k + 1 > above ? k + 1 - above : 0, hi = std::min(below, k + 1);
    while (lo < hi) {
      const std::size_t i = lo + (hi - lo) / 2;
      const std::size_t j = k + 1 - i;
      if (j > 0 && i < below && high(j - 1) > low(i)) lo = i + 1;
      else hi = i;
    }
    const std::size_t j = k + 1 - lo;
    double v = -std::numeric_limits<double>::infinity();
    if (lo > 0) v = low(lo - 1);
    if (j > 0) v = std::max(v, high(j - 1));
    return v;
  };
  return n % 2 == 1 ? select(n / 2) : 0.5 * (select(n / 2 - 1) + select(n / 2));
}

}  // namespace gyrotherm::fit
