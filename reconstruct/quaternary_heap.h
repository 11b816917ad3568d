// A priority queue over a 4-ary heap: the same interface and order as
// std::priority_queue (top is the largest by operator<), with half the depth,
// so a pop touches fewer cache lines. Constriction pops once per removed
// cell, and the heap of a million-point input outgrows the caches.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace scanstation {

template <typename T>
class QuaternaryHeap {
 public:
  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  const T& top() const { return items_.front(); }

  void push(const T& item) {
    std::size_t i = items_.size();
    items_.push_back(item);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!(items_[parent] < item)) break;
      items_[i] = std::move(items_[parent]);
      i = parent;
    }
    items_[i] = item;
  }

  void pop() {
    T last = std::move(items_.back());
    items_.pop_back();
    if (items_.empty()) return;
    const std::size_t n = items_.size();
    std::size_t i = 0;
    for (;;) {
      const std::size_t first = 4 * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + 4 < n ? first + 4 : n;
      for (std::size_t c = first + 1; c < end; ++c)
        if (items_[best] < items_[c]) best = c;
      if (!(last < items_[best])) break;
      items_[i] = std::move(items_[best]);
      i = best;
    }
    items_[i] = std::move(last);
  }

 private:
  std::vector<T> items_;
};

}  // namespace scanstation
