#include "message_definitions.h"

#include <initializer_list>

namespace contour_reg::io::detail {
namespace {

struct Used {
  const char *name, *text;
};

// The messages several definitions use.
constexpr Used kHeader{"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"};
constexpr Used kTime{"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"};
constexpr Used kVector3{"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"};
constexpr Used kQuaternion{"geometry_msgs/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"};

std::string withUsed(const std::string &text, std::initializer_list<Used> used) {
  std::string definition = text;
  for (const Used &u : used) definition += std::string(80, '=') + "\nMSG: " + u.name + "\n" + u.text;
  return definition;
}

}  // namespace

std::string messageDefinition(const std::string &type) {
  if (type == "sensor_msgs/msg/LaserScan")
    return withUsed(
        "std_msgs/Header header\n"
        "float32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
        "float32 time_increment\nfloat32 scan_time\n"
        "float32 range_min\nfloat32 range_max\n"
        "float32[] ranges\nfloat32[] intensities\n",
        {kHeader, kTime});
  if (type == "nav_msgs/msg/Odometry")
    return withUsed(
        "std_msgs/Header header\nstring child_frame_id\n"
        "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
        {kHeader,
         kTime,
         {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
         {"geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
         {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
         kQuaternion,
         {"geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
         {"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
         kVector3});
  if (type == "tf2_msgs/msg/TFMessage")
    return withUsed(
        "geometry_msgs/TransformStamped[] transforms\n",
        {{"geometry_msgs/TransformStamped",
          "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
         kHeader,
         kTime,
         {"geometry_msgs/Transform", "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
         kVector3,
         kQuaternion});
  return "";
}

}  // namespace contour_reg::io::detail
