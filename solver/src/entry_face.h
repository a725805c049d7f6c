// SPDX-License-Identifier: MIT
// The face of a static or kinematic body that a dynamic body came in through.
//
// Least-overlap push-out goes wrong against immovable bodies in two ways. At the join of two flush
// tiles, a box whose leading edge pokes past the join by less than gravity sank it overlaps the
// next tile least along x, and is stopped dead (or shoved sideways when it lands there). And a box
// that travelled past an immovable body's centre in one step comes out on the far side. Both are
// questions of where the body came from, so the face is read from motion, not depth:
//   - Along each axis, the body was outside the immovable body at the start of the step (its start
//     position relative to the immovable body's start, so a kinematic body's own motion counts)
//     or already inside. A face can be entered only along an axis it was outside on.
//   - Outside on one axis only: that axis's face, on the side the body started on; but see
//     "a step later" below.
//   - Outside on both (it came in over a corner): a face the body started level with (within
//     the touch tolerance) that nothing but this step's gravity sink (g dt^2) closed is one it
//     slid along, so it is the face: the body was held up at that level until the step began,
//     and judging its path as one straight segment would have it cross that plane at once. A box
//     crossing a gap no wider than itself so comes out on the far ground's top, not its side.
//     Otherwise the axis it crossed into last. That is the x face of the next tile for a box
//     sliding onto it; but a face that flush immovable bodies cover (the join between tiles) is
//     no way in, so then the other face is taken: the next tile's top, as if the tiles were one
//     surface. Flush means within WorldDef::touch_tolerance.
//   - A step later: a body that was level with a face a step ago, sank below it by that step's
//     gravity alone and touched its corner along the other axis when this step began (within
//     the tolerance, so no contact then: a box exactly as wide as a gap ends a step touching both
//     corners), and moves in along that axis now, slid along that face too.
//   - Inside on both at the start (created overlapping, or left so by a crush): least overlap.
// The resolver also resolves a body's immovable contacts in the order it entered them, so a box
// resting on one tile is pushed up out of it before the next tile's corner is looked at.
#pragma once

#include "step_context.h"

#include <cstdint>

namespace chain::detail {

struct Face {
  int axis;      // 0 = x, 1 = y
  int sign;      // the direction the dynamic body is pushed out along axis (+1 or -1)
  double entry;  // when it crossed that face's plane, as a fraction of the step's relative motion;
                 // below 0 (or -infinity) when it was inside along that axis at the start
};

// The face of immovable body b through which dynamic body a came to overlap it.
Face entry_face(const StepContext& ctx, std::uint32_t a, std::uint32_t b);

// True when the face of immovable body b on side `side` along `axis` is covered over [lo, hi]
// (along the other axis) by other immovable bodies flush against it that collide with body a: a
// join, not an edge.
bool face_covered(const StepContext& ctx, std::uint32_t a, std::uint32_t b, int axis, int side,
                  double lo, double hi);

}  // namespace chain::detail
