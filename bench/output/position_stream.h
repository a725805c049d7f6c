// SPDX-License-Identifier: MIT
// The positions of a replay page (replay_page.h), compact: each body's centre after each step as
// a whole number of quanta from its initial centre, and only the bodies whose number changed
// since the last state written. A body at rest costs nothing; one in motion about three bytes a
// step. The page's script (bench/replay/js/positions.js) reads the same bytes.
//
// Bytes, state after state (state 1, 2, ...; state 0 is every body at its initial centre):
//   varint  records in this state
//   per record, bodies in increasing order:
//     varint  2 * (body - next body after the previous record, or body for the first) + lost
//     unless lost: zigzag varint dx, dy, the change of the body's quantised offset (x - x0) / q
// A body is lost while its position is not finite or more than 2^50 quanta from where it
// started; its offset counts as (0, 0) while lost. Varints are 7 bits a byte, low bits first.
#pragma once

#include "model/scene.h"

#include <cstdint>
#include <span>
#include <vector>

namespace chainbench {

// The quantum of a scene's replay: 1/4096 of its smallest box edge (of the bodies that can move,
// else of any), rounded down to a power of two so that offsets times the quantum are exact.
double replay_quantum(const Scene& scene);

class PositionStream {
 public:
  PositionStream(std::vector<Vec2d> origins, double quantum);
  // Appends the next state: every body's centre, in scene order.
  void add(std::span<const Vec2d> positions);
  int states() const { return states_; }  // added so far
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  // The states 0, stride, 2 * stride, ... and the last one, as a stream of their own (each
  // record the change since the state before it in the new stream).
  std::vector<std::uint8_t> decimated(int stride) const;

  // One body's quantised offset in a decoded state.
  struct Offset {
    std::int64_t x = 0, y = 0;
    bool lost = false;
  };
  // Every state of `bytes` for `bodies` bodies, state 0 included (tests and decimation).
  static std::vector<std::vector<Offset>> decode(std::span<const std::uint8_t> bytes,
                                                 std::size_t bodies);

 private:
  std::vector<Vec2d> origins_;
  double quantum_;
  std::vector<Offset> last_;  // per body: its offset in the last state added
  std::vector<std::uint8_t> bytes_;
  int states_ = 0;
};

}  // namespace chainbench
