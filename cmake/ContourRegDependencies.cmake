# Third-party packages, all from Debian (see setup.sh).
#
# On Debian 12, PCL's config pulls in VTK, whose config names the target MPI::MPI_C;
# finding MPI first (C is enabled in project()) lets that resolve. Only the PCL
# components this project links are requested.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(MPI QUIET COMPONENTS C)
find_package(PCL 1.10 REQUIRED COMPONENTS common search kdtree features filters registration io)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs)
find_package(ZLIB REQUIRED)
find_package(yaml-cpp REQUIRED)
# ROS 2 bags: SQLite for the sqlite3 storage, Zstandard and LZ4 for the chunks of MCAP files.
find_package(SQLite3 REQUIRED)
find_path(ZSTD_INCLUDE_DIR zstd.h REQUIRED)
find_library(ZSTD_LIBRARY zstd REQUIRED)
find_path(LZ4_INCLUDE_DIR lz4frame.h REQUIRED)
find_library(LZ4_LIBRARY lz4 REQUIRED)
find_package(Threads REQUIRED)
option(CONTOUR_REG_WITH_ROSBAG "Read ROS 1 bags when Debian's rosbag_storage is installed" ON)
if(CONTOUR_REG_WITH_ROSBAG)
  find_package(RosbagStorage)
endif()
if(CONTOUR_REG_BUILD_APPS)
  find_package(CLI11 CONFIG REQUIRED)
endif()
if(BUILD_TESTING)
  find_package(GTest REQUIRED)
endif()
if(CONTOUR_REG_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
# The Python module: Debian's python3, NumPy and pybind11 (python3-dev, python3-numpy,
# pybind11-dev). The system interpreter is preferred over any other on the PATH, since
# Debian's NumPy and pytest belong to it.
if(CONTOUR_REG_BUILD_PYTHON)
  if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG)
  if(NOT Python3_FOUND OR NOT pybind11_FOUND)
    message(FATAL_ERROR "The Python module needs python3-dev and pybind11-dev (./setup.sh installs them); "
                        "or configure with -DCONTOUR_REG_BUILD_PYTHON=OFF")
  endif()
endif()
