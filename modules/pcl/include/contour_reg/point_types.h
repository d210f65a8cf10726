#pragma once
/// @file point_types.h
/// Point type of a contour special point, registered with PCL.

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

namespace contour_reg {

/// A corner special point of a scan contour, as ContourCornerEstimation outputs it.
///
/// x, y: corner vertex in the scan frame (m), z = 0. corner_angle: angle between the arms
/// (rad). orientation: direction of the bisector into the corner's opening (rad).
/// response: matched-filter output c(n), eq. (13). turn: +1 left / -1 right along the
/// contour. fragment: the local fragment of eq. (14), kFragmentElements elementary vectors
/// centred on the vertex as (re, im) pairs, zero-padded when the contour ends or L is
/// smaller than kFragmentElements / 2.
struct EIGEN_ALIGN16 ContourCorner {
  static constexpr int kFragmentElements = 16;
  PCL_ADD_POINT4D;
  float corner_angle;
  float orientation;
  float response;
  float turn;
  float fragment[2 * kFragmentElements];
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace contour_reg

// clang-format off
POINT_CLOUD_REGISTER_POINT_STRUCT(contour_reg::ContourCorner,
  (float, x, x)
  (float, y, y)
  (float, z, z)
  (float, corner_angle, corner_angle)
  (float, orientation, orientation)
  (float, response, response)
  (float, turn, turn)
  (float[32], fragment, fragment))
// clang-format on
