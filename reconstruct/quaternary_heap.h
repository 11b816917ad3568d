// A priority queue over a 4-ary heap: the same interface and order as
// std::priority_queue (top is the largest by operator<), with half the depth,
// so a pop touches fewer cache lines. Constriction pops once per removed
// cell, and the heap of a million-point input outgrows the caches.
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
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

/// The same order as QuaternaryHeap (top is the largest by operator<), for
/// queues where most items are never popped: constriction pushes every cell
/// as soon as it is removable, and in 2D about a third of them (the cells on
/// the inner side of the curve, keyed near +1) wait until the end. Only the
/// items that come no later than a limit sit in the heap, the others in an
/// unordered list; when the heap runs dry, the best part of the list (an
/// eighth, by a selection) joins it. The heap stays small enough for the
/// caches, and an item that is never popped costs a few list passes.
template <typename T>
class TieredQueue {
 public:
  bool empty() const { return heap_.empty() && rest_.empty(); }
  std::size_t size() const { return heap_.size() + rest_.size(); }
  const T& top() {
    if (heap_.empty()) refill();
    return heap_.top();
  }
  void push(const T& item) {
    if (limit_ && !(item < *limit_)) {
      heap_.push(item);
    } else {
      rest_.push_back(item);
    }
  }
  void pop() {
    if (heap_.empty()) refill();
    heap_.pop();
  }

 private:
  void refill() {
    const std::size_t n = rest_.size();
    const std::size_t k = std::min(n, std::max<std::size_t>(n / 8, 1024));
    if (k == 0) return;
    const auto cut = rest_.end() - static_cast<std::ptrdiff_t>(k);
    std::nth_element(rest_.begin(), cut, rest_.end());
    limit_ = *cut;  // the k items from cut on come no later than it; so may equal ones before
    const auto first = std::partition(rest_.begin(), cut, [&](const T& item) { return item < *limit_; });
    for (auto it = first; it != rest_.end(); ++it) heap_.push(*it);
    rest_.erase(first, rest_.end());
  }

  QuaternaryHeap<T> heap_;  // every item that is not below limit_
  std::vector<T> rest_;     // the items below limit_ (all of them before the first refill)
  std::optional<T> limit_;
};

}  // namespace scanstation
