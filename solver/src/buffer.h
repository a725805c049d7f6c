// SPDX-License-Identifier: MIT
// How the step's per-body and per-pair buffers grow: by a quarter, not by doubling. A buffer is
// grown when the world gains bodies or contacts, and then kept (no allocation in later steps); a
// vector's own growth would double it for one body more, and a world of 10,000 bodies that gained
// one held some 150 bytes a body more than it needed (tests/solver/allocation_test.cpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace chain::detail {

// v.resize(n), with any new capacity at least a quarter (and 8 elements) more than the old.
template <class T>
void resize_buffer(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max(n, v.capacity() + v.capacity() / 4 + 8));
  v.resize(n);
}

// v.assign(n, value), growing as resize_buffer().
template <class T>
void assign_buffer(std::vector<T>& v, std::size_t n, const std::type_identity_t<T>& value) {
  if (n > v.capacity()) v.reserve(std::max(n, v.capacity() + v.capacity() / 4 + 8));
  v.assign(n, value);
}

// v.reserve(n), growing as resize_buffer().
template <class T>
void reserve_buffer(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max(n, v.capacity() + v.capacity() / 4 + 8));
}

// Room for one more element (a push_back that allocates nothing), growing as resize_buffer().
template <class T>
void reserve_one_more(std::vector<T>& v) {
  if (v.size() == v.capacity()) v.reserve(v.size() + v.size() / 4 + 16);
}

// v.push_back(value), growing as resize_buffer().
template <class T>
void push_buffer(std::vector<T>& v, const std::type_identity_t<T>& value) {
  reserve_one_more(v);
  v.push_back(value);
}

}  // namespace chain::detail
