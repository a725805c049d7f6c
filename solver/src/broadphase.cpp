#include "broadphase.h"

#include <bit>
#include <limits>

namespace chain::detail {
namespace {

constexpr double kMinCell = 1.0e-6;
constexpr double kMaxCell = 1.0e9;
constexpr std::uint32_t kMaxCellsPerAxis = 1u << 30;

double largest_half(const Bodies& b, std::uint32_t i) {
  return std::max(b.hx[i], b.hy[i]);
}

std::uint32_t cells_spanned(double lo, double hi, double inv_cell) {
  const double span = std::floor((hi - lo) * inv_cell);
  if (!(span < static_cast<double>(kMaxCellsPerAxis - 1))) return kMaxCellsPerAxis;
  return static_cast<std::uint32_t>(span) + 1;
}

}  // namespace

void Broadphase::configure(const Bodies& bodies) {
  const std::uint32_t n = bodies.size();
  // Size cells for the movable bodies: they are the ones that meet each other every step.
  std::vector<double> halves;
  const std::uint32_t sized = bodies.movable_end > 0 ? bodies.movable_end : n;
  halves.reserve(sized);
  for (std::uint32_t i = 0; i < sized; ++i)
    halves.push_back(largest_half(bodies, i));
  double p90 = 0.5;
  if (!halves.empty()) {
    const auto k = static_cast<std::ptrdiff_t>((halves.size() - 1) * 9 / 10);
    std::nth_element(halves.begin(), halves.begin() + k, halves.end());
    p90 = halves[static_cast<std::size_t>(k)];
  }
  cell_ = std::clamp(2.0 * p90, kMinCell, kMaxCell);
  inv_cell_ = 1.0 / cell_;

  grid_bodies_.clear();
  large_.clear();
  small_half_ = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (largest_half(bodies, i) <= 0.5 * cell_) {
      grid_bodies_.push_back(i);
      small_half_ = std::max(small_half_, largest_half(bodies, i));
    } else {
      large_.push_back(i);
    }
  }
  const std::uint32_t table = std::bit_ceil(
      std::max<std::uint32_t>(64u, 2u * static_cast<std::uint32_t>(grid_bodies_.size())));
  mask_ = table - 1;
  cell_start_.assign(table + 1, 0);
  cursor_.assign(table, 0);
  keys_.resize(grid_bodies_.size());
  key_x_.resize(grid_bodies_.size());
  key_y_.resize(grid_bodies_.size());
  entries_.resize(grid_bodies_.size());
  build_x_.resize(n);
  build_y_.resize(n);
}

void Broadphase::build(const Bodies& bodies) {
  margin_ = 0.0;
  std::copy(bodies.x.begin(), bodies.x.end(), build_x_.begin());
  std::copy(bodies.y.begin(), bodies.y.end(), build_y_.begin());
  if (grid_bodies_.empty()) {
    width_ = height_ = 1;
    return;
  }

  double min_x = std::numeric_limits<double>::max(), min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest(), max_y = max_x;
  for (const std::uint32_t i : grid_bodies_) {
    min_x = std::min(min_x, bodies.x[i]);
    max_x = std::max(max_x, bodies.x[i]);
    min_y = std::min(min_y, bodies.y[i]);
    max_y = std::max(max_y, bodies.y[i]);
  }
  origin_x_ = min_x;
  origin_y_ = min_y;
  width_ = cells_spanned(min_x, max_x, inv_cell_);
  height_ = cells_spanned(min_y, max_y, inv_cell_);

  // Counting sort of the grid bodies by bucket; stable, so solve order holds within a bucket.
  std::fill(cell_start_.begin(), cell_start_.end(), 0u);
  for (std::size_t k = 0; k < grid_bodies_.size(); ++k) {
    const std::uint32_t i = grid_bodies_[k];
    key_x_[k] = cell_x(bodies.x[i]);
    key_y_[k] = cell_y(bodies.y[i]);
    keys_[k] = bucket(key_x_[k], key_y_[k]);
    ++cell_start_[keys_[k] + 1];
  }
  for (std::size_t b = 1; b < cell_start_.size(); ++b)
    cell_start_[b] += cell_start_[b - 1];
  std::copy(cell_start_.begin(), cell_start_.end() - 1, cursor_.begin());
  for (std::size_t k = 0; k < grid_bodies_.size(); ++k) {
    const std::uint32_t i = grid_bodies_[k];
    entries_[cursor_[keys_[k]]++] = Entry{i,
                                          key_x_[k],
                                          key_y_[k],
                                          bodies.immovable(i) ? 1u : 0u,
                                          bodies.x[i] - bodies.hx[i],
                                          bodies.y[i] - bodies.hy[i],
                                          bodies.x[i] + bodies.hx[i],
                                          bodies.y[i] + bodies.hy[i]};
  }
}

}  // namespace chain::detail
