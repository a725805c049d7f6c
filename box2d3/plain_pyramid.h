// SPDX-License-Identifier: MIT
// A Box2D v3 world built by hand with the plain v3 API: the `pyramid` scene (base boxes of 1 m,
// 1 kg, no friction, on a static ground), fixed rotation, sleeping off, stepped at 1/60 s with
// `substeps` sub-steps. The benchmark times it beside the box2d3 engine on the same scene, so
// that whatever the adapter adds is in plain view.
#pragma once

#include <cstddef>
#include <memory>

namespace chainbench {

class PlainBox2d3Pyramid {
 public:
  PlainBox2d3Pyramid(int base, int substeps);
  ~PlainBox2d3Pyramid();
  PlainBox2d3Pyramid(const PlainBox2d3Pyramid&) = delete;
  PlainBox2d3Pyramid& operator=(const PlainBox2d3Pyramid&) = delete;

  void step();
  std::size_t bodies() const { return bodies_; }

 private:
  struct World;
  std::unique_ptr<World> world_;
  std::size_t bodies_ = 0;
  int substeps_;
};

}  // namespace chainbench
