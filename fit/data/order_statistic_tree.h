#pragma once
// A multiset of numbers kept in order, for a sliding window's median and
// median absolute deviation (the glitch rule, fit/data/hampel.h) in O(log n)
// a step instead of O(n):
//
//   insert(x, id), erase(x, id)   O(log n) expected
//   kth(k)                        O(log n) expected: the k-th smallest, from 0
//   median()                      O(log n): the middle value, or the mean of
//                                 the two middle values (fit/data/median.h's)
//   median_abs_deviation(m)       O(log² n): median_j |x_j − m|
//
// A treap (Seidel and Aragon): a binary search tree on (x, id) whose nodes
// are also a heap in pseudo-random priorities (a hash of id), so its expected
// depth is O(log n) whatever order the values come in; each node counts the
// nodes below it, so the k-th smallest is one walk from the root. Equal values
// are told apart by their id (a window gives each sample its sequence number):
// erase removes the one inserted with that id.
//
// The deviation's median is a selection in two sorted sequences: the values
// at or below m, read downwards, give |x − m| in increasing order, and those
// above it, read upwards, too; the k-th smallest of the two is found by
// bisection on how many come from the first (O(log n) steps of two kth()).
// The numbers are the ones a sort of every |x_j − m| would give, bit for bit.
//
// Values must not be NaN (they are ordered by <). Nodes live in one array and
// are reused, so a window of steady size allocates nothing.
//
// References: R. Seidel, C. R. Aragon, "Randomized search trees",
// Algorithmica 16 (1996) 464-497; the selection of the k-th smallest of two
// sorted arrays, e.g. G. N. Frederickson, D. B. Johnson, "The complexity of
// selection and ranking in X + Y and matrices with sorted columns", J. Comput.
// Syst. Sci. 24 (1982) 197-208.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyrotherm::fit {

class OrderStatisticTree {
 public:
  void insert(double x, std::uint64_t id);
  // The element inserted as (x, id) must be there.
  void erase(double x, std::uint64_t id);
  void clear();
  std::size_t size() const { return root_ < 0 ? 0 : nodes_[static_cast<std::size_t>(root_)].size; }
  // k < size().
  double kth(std::size_t k) const;
  // NaN for an empty tree, as median_in_place.
  double median() const;
  double median_abs_deviation(double m) const;

 private:
  struct Node {
    double x;
    std::uint64_t id;
    std::uint64_t priority;
    std::int32_t left, right;
    std::uint32_t size;
  };
  Node& at(std::int32_t n) { return nodes_[static_cast<std::size_t>(n)]; }
  const Node& at(std::int32_t n) const { return nodes_[static_cast<std::size_t>(n)]; }
  std::uint32_t size_of(std::int32_t n) const { return n < 0 ? 0 : at(n).size; }
  void update(std::int32_t n) { at(n).size = 1 + size_of(at(n).left) + size_of(at(n).right); }
  bool before(double x, std::uint64_t id, std::int32_t n) const {
    return x < at(n).x || (!(at(n).x < x) && id < at(n).id);
  }
  // Splits t into the nodes before (x, id) and those after it.
  void split(std::int32_t t, double x, std::uint64_t id, std::int32_t& before_part, std::int32_t& after_part);
  std::int32_t merge(std::int32_t a, std::int32_t b);
  std::int32_t insert_at(std::int32_t t, std::int32_t n);
  std::int32_t erase_at(std::int32_t t, double x, std::uint64_t id);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> free_;
  std::int32_t root_ = -1;
};

}  // namespace gyrotherm::fit
