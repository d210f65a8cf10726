#pragma once
/// @file lazy_kdtree.h
/// A pcl::search::KdTree that builds its index on the first query, not when its cloud is set.
///
/// pcl::Registration builds a kd-tree over every new target in align(), because ICP needs
/// it. The contour method does not; only getFitnessScore() does. With this tree the
/// build is paid only when something searches.
///
/// A query that is not finite has no neighbours. The contour classes take scans with a NaN
/// point for each beam without a return, and PCL's getFitnessScore() searches for every
/// source point, which FLANN refuses with an assertion; it also reads the first distance
/// whatever the count found, so that query answers 0 with one index -1 at an infinite
/// distance, which the score skips.

#include <limits>
#include <mutex>

#include <pcl/common/point_tests.h>
#include <pcl/search/kdtree.h>

namespace contour_reg {

template <typename PointT>
class LazyKdTree : public pcl::search::KdTree<PointT> {
 public:
  using Base = pcl::search::KdTree<PointT>;
  using typename Base::IndicesConstPtr;
  using typename Base::PointCloudConstPtr;

  LazyKdTree() : Base(false) {}

  void setInputCloud(const PointCloudConstPtr &cloud, const IndicesConstPtr &indices = IndicesConstPtr()) override {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_cloud_ = cloud;
    pending_indices_ = indices;
    this->input_ = cloud;  // what getInputCloud() reports, before the index exists
    this->indices_ = indices;
    built_ = false;
  }

  int nearestKSearch(const PointT &point, int k, pcl::Indices &indices, std::vector<float> &distances) const override {
    if (!pcl::isXYZFinite(point)) {
      indices.assign(1, -1);
      distances.assign(1, std::numeric_limits<float>::infinity());
      return 0;
    }
    build();
    return Base::nearestKSearch(point, k, indices, distances);
  }

  int radiusSearch(const PointT &point, double radius, pcl::Indices &indices, std::vector<float> &distances,
                   unsigned int max_nn = 0) const override {
    if (!pcl::isXYZFinite(point)) {
      indices.clear();
      distances.clear();
      return 0;
    }
    build();
    return Base::radiusSearch(point, radius, indices, distances, max_nn);
  }

 private:
  // Queries are const in PCL's interface; the index is a cache of the pending cloud.
  void build() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (built_ || !pending_cloud_) return;
    auto *self = const_cast<LazyKdTree *>(this);
    self->Base::setInputCloud(pending_cloud_, pending_indices_);
    built_ = true;
  }

  PointCloudConstPtr pending_cloud_;
  IndicesConstPtr pending_indices_;
  mutable bool built_ = false;
  mutable std::mutex mutex_;
};

}  // namespace contour_reg
