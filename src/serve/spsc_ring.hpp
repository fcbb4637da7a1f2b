// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A bounded single-producer, single-consumer queue that never blocks either side: the physics
/// thread pushes (a tick's duration, the hand's sample), the display thread drains. When the
/// consumer falls behind and the ring is full, push drops the value and counts it.
#include <atomic>
#include <cstddef>
#include <vector>

namespace roifem::serve {

template <class T>
class SpscRing {
 public:
  /// capacity: rounded up to a power of two.
  explicit SpscRing(std::size_t capacity) {
    std::size_t size = 1;
    while (size < capacity) size *= 2;
    slots_.resize(size);
    mask_ = size - 1;
  }
  /// Producer only. False (and counted) when full.
  bool push(const T& value) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) > mask_) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    slots_[head & mask_] = value;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }
  /// Consumer only: appends everything queued to `out`; returns how many.
  std::size_t drain(std::vector<T>& out) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t head = head_.load(std::memory_order_acquire);
    for (std::size_t k = tail; k != head; ++k) out.push_back(slots_[k & mask_]);
    tail_.store(head, std::memory_order_release);
    return head - tail;
  }
  std::size_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  std::vector<T> slots_;
  std::size_t mask_ = 0;
  std::atomic<std::size_t> head_{0}, tail_{0}, dropped_{0};
};

}  // namespace roifem::serve
