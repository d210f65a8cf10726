#pragma once
/// @file spare_elements.h
/// Reuse of the buffers that a vector's elements own.
///
/// A scan's features are vectors of objects that own buffers of their own (a segment's
/// points, a contour's vertices). Clearing such a vector frees every one of those buffers, and
/// the next scan allocates them again. SpareElements keeps the surplus elements instead, and
/// hands them back when a vector grows, so that extracting features scan after scan into the
/// same objects allocates only while the buffers are still growing.

#include <cstddef>
#include <utility>
#include <vector>

namespace contour_reg {

template <typename T>
class SpareElements {
 public:
  /// Makes `items` n elements long. Surplus elements are kept here; missing ones are taken
  /// from those kept (with their old contents) before new ones are made.
  void resize(std::vector<T> &items, std::size_t n) {
    while (items.size() > n) {
      kept_.push_back(std::move(items.back()));
      items.pop_back();
    }
    while (items.size() < n) append(items);
  }

  /// Keeps every element of `items`, leaving it empty.
  void clear(std::vector<T> &items) { resize(items, 0); }

  /// Appends an element to `items`, one kept here (with its old contents) if there is one.
  T &append(std::vector<T> &items) {
    if (kept_.empty()) return items.emplace_back();
    items.push_back(std::move(kept_.back()));
    kept_.pop_back();
    return items.back();
  }

  /// Keeps the last element of `items`.
  void dropLast(std::vector<T> &items) {
    kept_.push_back(std::move(items.back()));
    items.pop_back();
  }

 private:
  std::vector<T> kept_;
};

}  // namespace contour_reg
