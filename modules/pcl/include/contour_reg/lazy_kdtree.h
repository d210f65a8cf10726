#pragma once
/// @file lazy_kdtree.h
/// A pcl::search::KdTree that builds its index on the first query, not when its cloud is set.
///
/// pcl::Registration builds a kd-tree over every new target in align(), because ICP needs
/// it. The contour method does not; only getFitnessScore() does. With this tree the
/// build is paid only when something searches.

#include <mutex>

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
    build();
    return Base::nearestKSearch(point, k, indices, distances);
  }

  int radiusSearch(const PointT &point, double radius, pcl::Indices &indices, std::vector<float> &distances,
                   unsigned int max_nn = 0) const override {
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
