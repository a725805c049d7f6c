// SPDX-License-Identifier: MIT
// A list of body slots appended to without a capacity check per element.
//
// Room is made first (room_for, which grows the list out of line when it must) and push() then
// only writes. The walls' loop gathers its candidates this way: std::vector::push_back has its
// growing path, a call, inside the walk, and around that call the compiler kept the loop's values
// on the stack and reloaded them for every wall.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace chain::detail {

class SlotList {
 public:
  void room_for(std::size_t more) {
    if (size_ + more > slots_.size()) [[unlikely]]
      grow(size_ + more);
  }
  void push(std::uint32_t slot) { slots_[size_++] = slot; }  // after room_for
  void clear() { size_ = 0; }
  // Keeps the first `size` slots (at most size()): a list used as a stack of lists.
  void truncate(std::size_t size) { size_ = size; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint32_t operator[](std::size_t k) const { return slots_[k]; }
  const std::uint32_t* begin() const { return slots_.data(); }
  const std::uint32_t* end() const { return slots_.data() + size_; }

 private:
  [[gnu::noinline]] void grow(std::size_t at_least) {
    slots_.resize(std::max(at_least, 2 * slots_.size()));
  }

  std::vector<std::uint32_t> slots_;  // sized to the capacity: the first size_ hold the list
  std::size_t size_ = 0;
};

}  // namespace chain::detail
