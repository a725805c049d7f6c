// SPDX-License-Identifier: MIT
#include "output/position_stream.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace chainbench {
namespace {

constexpr double kMaxQuanta = 1125899906842624.0;  // 2^50: offsets stay exact in a JS number

void put_varint(std::vector<std::uint8_t>& out, std::uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<std::uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<std::uint8_t>(v));
}

std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}

std::int64_t unzigzag(std::uint64_t v) {
  return static_cast<std::int64_t>(v >> 1) ^ -static_cast<std::int64_t>(v & 1);
}

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  bool done() const { return at_ == bytes_.size(); }
  std::uint64_t varint() {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (at_ == bytes_.size()) throw std::runtime_error("position stream: cut short");
      const std::uint8_t b = bytes_[at_++];
      v |= static_cast<std::uint64_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) return v;
    }
    throw std::runtime_error("position stream: varint too long");
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

using Offset = PositionStream::Offset;

// Appends the state `now` as its changes from `before` (which becomes `now`).
void put_state(std::vector<std::uint8_t>& out, std::vector<Offset>& before,
               const std::vector<Offset>& now) {
  std::uint64_t records = 0;
  for (std::size_t i = 0; i < now.size(); ++i) {
    const Offset &a = before[i], &b = now[i];
    records += a.x != b.x || a.y != b.y || a.lost != b.lost;
  }
  put_varint(out, records);
  std::size_t next = 0;
  for (std::size_t i = 0; i < now.size(); ++i) {
    const Offset &a = before[i], &b = now[i];
    if (a.x == b.x && a.y == b.y && a.lost == b.lost) continue;
    put_varint(out, 2 * (i - next) + (b.lost ? 1 : 0));
    if (!b.lost) {
      put_varint(out, zigzag(b.x - a.x));
      put_varint(out, zigzag(b.y - a.y));
    }
    next = i + 1;
  }
  before = now;
}

}  // namespace

double replay_quantum(const Scene& scene) {
  double edge = HUGE_VAL;
  for (const bool moving_only : {true, false}) {
    for (const SceneBody& b : scene.bodies) {
      if (moving_only && b.kind == BodyKind::kStatic) continue;
      edge = std::min(edge, 2.0 * std::min(b.half_extents.x, b.half_extents.y));
    }
    if (std::isfinite(edge)) break;
  }
  if (!std::isfinite(edge) || edge <= 0.0) edge = 1.0;
  return std::exp2(std::floor(std::log2(edge / 4096.0)));
}

PositionStream::PositionStream(std::vector<Vec2d> origins, double quantum)
    : origins_(std::move(origins)), quantum_(quantum), last_(origins_.size()) {}

void PositionStream::add(std::span<const Vec2d> positions) {
  std::vector<Offset> now(origins_.size());
  for (std::size_t i = 0; i < now.size(); ++i) {
    const double qx = std::round((positions[i].x - origins_[i].x) / quantum_);
    const double qy = std::round((positions[i].y - origins_[i].y) / quantum_);
    if (std::abs(qx) <= kMaxQuanta && std::abs(qy) <= kMaxQuanta) {  // false for NaN
      now[i] = {static_cast<std::int64_t>(qx), static_cast<std::int64_t>(qy), false};
    } else {
      now[i] = {0, 0, true};
    }
  }
  put_state(bytes_, last_, now);
  ++states_;
}

namespace {

// Calls fn(state number, offsets) for every state of `bytes`, state 0 first.
template <class Fn>
void for_each_state(std::span<const std::uint8_t> bytes, std::size_t bodies, Fn&& fn) {
  std::vector<Offset> state(bodies);
  int number = 0;
  fn(number, state);
  Reader in(bytes);
  while (!in.done()) {
    const std::uint64_t records = in.varint();
    std::size_t next = 0;
    for (std::uint64_t r = 0; r < records; ++r) {
      const std::uint64_t head = in.varint();
      const std::size_t body = next + static_cast<std::size_t>(head >> 1);
      if (body >= bodies) throw std::runtime_error("position stream: body out of range");
      Offset& o = state[body];
      if (head & 1) {
        o = {0, 0, true};
      } else {
        if (o.lost) o = {};
        o.x += unzigzag(in.varint());
        o.y += unzigzag(in.varint());
      }
      next = body + 1;
    }
    fn(++number, state);
  }
}

}  // namespace

std::vector<std::vector<Offset>> PositionStream::decode(std::span<const std::uint8_t> bytes,
                                                        std::size_t bodies) {
  std::vector<std::vector<Offset>> states;
  for_each_state(bytes, bodies, [&](int, const std::vector<Offset>& s) { states.push_back(s); });
  return states;
}

std::vector<std::uint8_t> PositionStream::decimated(int stride) const {
  if (stride <= 1) return bytes_;
  std::vector<std::uint8_t> out;
  std::vector<Offset> before(origins_.size());
  for_each_state(bytes_, origins_.size(), [&](int number, const std::vector<Offset>& state) {
    if (number > 0 && (number % stride == 0 || number == states_)) put_state(out, before, state);
  });
  return out;
}

}  // namespace chainbench
