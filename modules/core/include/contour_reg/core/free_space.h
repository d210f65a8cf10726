#pragma once
/// @file free_space.h
/// Beyond the paper: free-space evidence against a motion.
///
/// A LIDAR beam that returns at range r has passed through free space up to r. When a motion
/// moves a surface point of the source scan to a spot that the target scan's beams saw
/// through (the point lies clearly in front of the target's measured range at that bearing),
/// the target contradicts the motion; the same holds the other way round. Contour fit alone
/// cannot see this: along a row of equally spaced doors, a motion one period off puts the
/// walls on the walls and the doors on the doors, but the corridor's end, a side opening or
/// a wall seen across it lands where the other scan looked through empty space.
///
/// The source's equalized contour is checked every 0.1 m; each point is compared with the two target beams that bracket
/// their bearing and must lie clearly in front of the nearer of the two ranges (FreeSpaceParams::margin), so that a
/// depth discontinuity between beams does not contradict a right motion. The margin is measured across the contour:
/// along a beam that meets the contour at an angle a it is margin / sin(a), so a wall in line with the beam (the beam
/// passed along it, not through it) never contradicts. Bearings where the target
/// has no valid return (no echo, a gap between segments) give no evidence. A moving person, a door swung open between
/// the scans contradict a right motion too, but they are small objects of their own: the contradictions of a contour
/// that spans less than `min_object_length` are not counted. On a larger contour, a wall, every contradicted point
/// counts, however short the stretch: a wrong motion may put most of a wall behind what the other scan saw and only
/// the stretch in line with a gap in front of it.

#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/bearing_buckets.h"
#include "contour_reg/core/contour_features.h"

namespace contour_reg {

struct FreeSpaceParams {
  /// Whether registration weighs free-space evidence: when it decides between distinct motions,
  /// against the motion it would accept (the `contradicted` verdict), and, beam by beam, for a
  /// motion of the contours that overlaps the target little (contradictedReturnShare).
  bool enabled = true;
  /// m, how far in front of the other scan's measured range a point must lie to contradict,
  /// measured across its contour: above range noise and what a right motion's residual error
  /// moves a point (a turn of 1 degree moves a point 30 m away by 0.5 m), below the offset of a
  /// distinct motion.
  double margin = 0.5;
  /// m, contours that span less than this (the farthest of their points from their first)
  /// may be objects that moved between the scans (a walking person, about 0.5 m across at the
  /// height of a LIDAR, a chair, a door leaf): their contradictions are not counted.
  double min_object_length = 1.0;

  bool validate(std::string *why = nullptr) const;
};

/// How much of one scan's contour a motion puts in the other scan's free space.
struct FreeSpaceEvidence {
  double tested_length = 0.0;        ///< m of contour that fell inside the other scan's view
  double contradicted_length = 0.0;  ///< m of contour in its free space, of contours min_object_length or larger
  int contradicted_runs = 0;         ///< in how many stretches
  /// The contradicted share of the tested contour (0 when nothing was tested).
  double fraction() const { return tested_length > 0.0 ? contradicted_length / tested_length : 0.0; }
  FreeSpaceEvidence &operator+=(const FreeSpaceEvidence &other);
};

/// Both pieces of evidence together.
inline FreeSpaceEvidence operator+(FreeSpaceEvidence a, const FreeSpaceEvidence &b) { return a += b; }

/// The target's view: the bearing and range of every point of its segments, by bearing.
class RangeView {
 public:
  RangeView() = default;
  explicit RangeView(const ContourFeatures &scan) { assign(scan); }
  /// Rebuilds the view of `scan`, reusing the buffers.
  void assign(const ContourFeatures &scan);
  /// Rebuilds the view of a scan's points in its sensor frame (a polar code: NaN points are
  /// no-returns and are skipped), isolated returns too.
  void assign(const ComplexSequence &points);
  /// The range the scan measured at `bearing` (rad): the nearer of the two bracketing
  /// returns, or a negative value where it has no evidence (outside its view, in a gap).
  double rangeAt(double bearing) const;
  /// m, how far a point (sensor frame) lies from the surface the scan measured at its bearing:
  /// the segment between the two returns that bracket it, or a negative value where it has no
  /// evidence. Along a wall the beams meet at a glancing angle the returns lie too far apart
  /// to form a contour, and the segment between two of them is still the wall.
  double distanceToSurface(const Eigen::Vector2d &point) const;

  /// What the view says of a point (sensor frame): no evidence at its bearing, whether the
  /// scan's beam there passed more than `margin` m beyond it (saw through it), or stopped more
  /// than `margin` m before it (the point is hidden behind what the scan saw).
  enum class Sight { kNoEvidence, kNotThrough, kSeenThrough, kHidden };
  Sight sightOf(const Eigen::Vector2d &point, double margin) const;

  /// Whether a point (sensor frame) lies within the scan's reach: between its first and last
  /// bearing (its field of view) and no farther than its farthest point (its range). Beyond
  /// it the scan could not have seen the point; the gaps between its returns lie within it.
  bool reaches(const Eigen::Vector2d &point) const;

 private:
  std::vector<double> bearings_, ranges_;
  std::vector<Eigen::Vector2d> points_;  // the returns, by bearing as bearings_
  BearingBuckets buckets_;               // over bearings_
  std::vector<double> spacing_;          // working memory of assign()
  void add(const Complex &point);
  void index();  // sorts by bearing, buckets the bearings and sets max_gap_
  // The returns lo and hi that bracket `bearing` (across the +-pi cut too); false where they
  // lie more than max_gap_ apart or there are fewer than two.
  bool bracket(double bearing, std::size_t &lo, std::size_t &hi) const;
  double max_gap_ = 0.0;   // rad, bracketing returns farther apart than this leave a gap
  double farthest_ = 0.0;  // m, the largest range
};

/// The evidence of `target`'s view against the source's contour moved by `motion` (source to
/// target). With `contradicted`, the checked points of the counted runs are appended to it,
/// moved into the target frame (for pictures).
FreeSpaceEvidence freeSpaceEvidence(const ContourFeatures &source, const RangeView &target_view,
                                    const Eigen::Matrix3d &motion, const FreeSpaceParams &params,
                                    std::vector<Eigen::Vector2d> *contradicted = nullptr);

/// Both ways: the source's contour in the target's view and the target's in the source's.
/// With `contradicted`, the points of both scans' counted runs are appended to it, in the target frame.
FreeSpaceEvidence mutualFreeSpaceEvidence(const ContourFeatures &source, const RangeView &source_view,
                                          const ContourFeatures &target, const RangeView &target_view,
                                          const Eigen::Matrix3d &motion, const FreeSpaceParams &params,
                                          std::vector<Eigen::Vector2d> *contradicted = nullptr);

/// Beam by beam: of the returns of both scans (sensor frames, isolated returns included,
/// non-finite points skipped) that fall inside the other scan's view, the share that `motion`
/// (source to target) puts more than `margin` m in front of the other's measured range along
/// its beam; 0 when none falls inside. Each view is RangeView::assign() of the other scan's
/// returns. No object size and no contour: a stand of table legs or a row of posts counts as
/// much as a wall.
double contradictedReturnShare(const ComplexSequence &source_returns, const RangeView &target_view,
                               const ComplexSequence &target_returns, const RangeView &source_view,
                               const Eigen::Matrix3d &motion, double margin);

}  // namespace contour_reg
