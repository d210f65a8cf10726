# Finds Debian's ROS 1 bag library (librosbag-storage-dev) and the message headers
# the bag reader needs (libsensor-msgs-dev, libnav-msgs-dev, libtf2-msgs-dev).
#
# Debian installs rosbag_storage beside ROS 2's pluginlib and class_loader, whose headers
# live one level deeper than rosbag/bag.h expects; their folders are added here.
# Sets RosbagStorage_FOUND, RosbagStorage_INCLUDE_DIRS and RosbagStorage_LIBRARIES
# (full paths, so an exported static library carries them to its users).
find_path(RosbagStorage_INCLUDE_DIR rosbag/bag.h)
find_path(RosbagStorage_SENSOR_MSGS_DIR sensor_msgs/LaserScan.h)
find_path(RosbagStorage_NAV_MSGS_DIR nav_msgs/Odometry.h)
find_path(RosbagStorage_TF2_MSGS_DIR tf2_msgs/TFMessage.h)
set(_rosbag_extra_dirs)
foreach(_header pluginlib/class_loader.hpp class_loader/multi_library_class_loader.hpp
                rcpputils/shared_library.hpp rcutils/shared_library.h ament_index_cpp/get_package_prefix.hpp)
  get_filename_component(_name ${_header} DIRECTORY)
  find_path(_rosbag_dir_${_name} ${_header} PATH_SUFFIXES ${_name})
  if(_rosbag_dir_${_name})
    list(APPEND _rosbag_extra_dirs ${_rosbag_dir_${_name}})
  endif()
endforeach()
set(RosbagStorage_LIBRARIES)
foreach(_library rosbag_storage roslz4 roscpp_serialization rostime cpp_common console_bridge boost_filesystem)
  find_library(RosbagStorage_${_library}_LIBRARY ${_library})
  if(RosbagStorage_${_library}_LIBRARY)
    list(APPEND RosbagStorage_LIBRARIES ${RosbagStorage_${_library}_LIBRARY})
  else()
    set(_rosbag_missing_library ${_library})
  endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(RosbagStorage
  REQUIRED_VARS RosbagStorage_INCLUDE_DIR RosbagStorage_SENSOR_MSGS_DIR RosbagStorage_NAV_MSGS_DIR
                RosbagStorage_TF2_MSGS_DIR
                RosbagStorage_rosbag_storage_LIBRARY RosbagStorage_roscpp_serialization_LIBRARY
                RosbagStorage_console_bridge_LIBRARY RosbagStorage_boost_filesystem_LIBRARY)
set(RosbagStorage_INCLUDE_DIRS ${RosbagStorage_INCLUDE_DIR} ${_rosbag_extra_dirs})
list(REMOVE_DUPLICATES RosbagStorage_INCLUDE_DIRS)
