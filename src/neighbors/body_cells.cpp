#include "particula/neighbors/body_cells.hpp"

namespace particula {

void BodyCells::build(const Domain& dom, real width, const std::vector<Item>& items) {
  dom_ = dom;
  const Vec2 L = dom.size();
  nx_ = std::max(1, static_cast<int>(L.x / width));
  ny_ = std::max(1, static_cast<int>(L.y / width));
  // counting sort by cell, stable
  start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  std::vector<std::size_t> cell_of(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) ++start_[(cell_of[k] = cell_index(items[k].centre)) + 1];
  for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
  std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
  ids_.resize(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) ids_[next[cell_of[k]]++] = items[k].id;
}

std::size_t BodyCells::cell_index(Vec2 x) const {
  const Vec2 w = dom_.wrap(x), L = dom_.size();
  const int cx = std::clamp(static_cast<int>((w.x - dom_.lo.x) / L.x * nx_), 0, nx_ - 1);
  const int cy = std::clamp(static_cast<int>((w.y - dom_.lo.y) / L.y * ny_), 0, ny_ - 1);
  return static_cast<std::size_t>(cy) * nx_ + cx;
}

}  // namespace particula
