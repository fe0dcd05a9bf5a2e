#pragma once
// A queue that is read at both ends and by position, in one array of a power
// of two slots used as a ring: what the glitch filter's sliding windows need
// (fit/data/hampel.h). Unlike std::deque, a window of steady size allocates
// nothing (std::deque allocates and frees a block every few elements as the
// window slides) and an element at a position is one mask away.
//
// The slots double when full (the elements keep their order); the first of
// them is at slot head_ & mask_. T must be default-constructible and
// copy-assignable.

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <vector>

namespace gyrotherm::fit {

template <class T>
class RingBuffer {
 public:
  bool empty() const { return head_ == tail_; }
  std::size_t size() const { return tail_ - head_; }
  // The element at position i from the front, i < size().
  T& operator[](std::size_t i) {
    assert(i < size());
    return slots_[(head_ + i) & mask_];
  }
  const T& operator[](std::size_t i) const {
    assert(i < size());
    return slots_[(head_ + i) & mask_];
  }
  T& front() { return (*this)[0]; }
  const T& front() const { return (*this)[0]; }
  T& back() { return (*this)[size() - 1]; }
  const T& back() const { return (*this)[size() - 1]; }

  void push_back(const T& value) {
    if (size() == slots_.size()) grow();
    slots_[tail_++ & mask_] = value;
  }
  void pop_front() {
    assert(!empty());
    ++head_;
  }
  void pop_back() {
    assert(!empty());
    --tail_;
  }
  void clear() { head_ = tail_ = 0; }

 private:
  void grow() {
    std::vector<T> bigger(std::max<std::size_t>(16, 2 * slots_.size()));
    const std::size_t n = size();
    for (std::size_t i = 0; i < n; ++i) bigger[i] = (*this)[i];
    slots_.swap(bigger);
    mask_ = slots_.size() - 1;
    head_ = 0;
    tail_ = n;
  }

  std::vector<T> slots_;
  std::size_t head_ = 0, tail_ = 0, mask_ = 0;  // positions counted since the start: size() = tail_ − head_
};

}  // namespace gyrotherm::fit
