# ROS 1 from Debian's packages (roscpp 1.15, tf2_ros, rosbag_storage, message headers),
# found without catkin. Defines PGMCL_HAVE_ROS and, when ON, two interface targets:
#   pgmcl_ros1_node_deps  roscpp, tf2_ros and the message headers the node uses
#   pgmcl_ros1_bag_deps   rosbag_storage (no master needed)
# ROS 1's generated message headers do not compile as C++20 (std::allocator<void>::rebind
# is gone), so translation units that include them are built as C++17 and talk to the
# C++20 code through plain-type bridge headers (mcl/rosbag_io, mcl/ros).
set(PGMCL_HAVE_ROS OFF)
set(PGMCL_ROS_BUILT OFF CACHE INTERNAL "The ROS 1 parts are built (cmake/demo.sh reads it)")
if(NOT PGMCL_WITH_ROS)
  return()
endif()
find_package(PkgConfig REQUIRED)
pkg_check_modules(PGMCL_ROSCPP QUIET IMPORTED_TARGET roscpp tf2_ros roscpp_serialization rostime)
set(_missing "")
if(NOT PGMCL_ROSCPP_FOUND)
  list(APPEND _missing "roscpp/tf2_ros (libroscpp-dev, libtf2-ros-dev)")
endif()
find_library(PGMCL_ROSBAG_STORAGE_LIB rosbag_storage)
find_path(PGMCL_ROSBAG_INCLUDE rosbag/bag.h)
find_path(PGMCL_PLUGINLIB_INCLUDE pluginlib/class_loader.hpp PATH_SUFFIXES pluginlib)
find_path(PGMCL_CLASS_LOADER_INCLUDE class_loader/multi_library_class_loader.hpp
  PATH_SUFFIXES class_loader)
find_path(PGMCL_RCPPUTILS_INCLUDE rcpputils/shared_library.hpp PATH_SUFFIXES rcpputils)
find_path(PGMCL_RCUTILS_INCLUDE rcutils/types.h PATH_SUFFIXES rcutils)
find_path(PGMCL_AMENT_INDEX_INCLUDE ament_index_cpp/get_package_prefix.hpp
  PATH_SUFFIXES ament_index_cpp)
if(NOT PGMCL_ROSBAG_STORAGE_LIB OR NOT PGMCL_ROSBAG_INCLUDE OR NOT PGMCL_PLUGINLIB_INCLUDE
   OR NOT PGMCL_CLASS_LOADER_INCLUDE OR NOT PGMCL_RCPPUTILS_INCLUDE OR NOT PGMCL_RCUTILS_INCLUDE
   OR NOT PGMCL_AMENT_INDEX_INCLUDE)
  list(APPEND _missing "rosbag_storage (librosbag-storage-dev)")
endif()
foreach(_msg sensor_msgs/LaserScan.h nav_msgs/OccupancyGrid.h nav_msgs/Odometry.h
    geometry_msgs/PoseWithCovarianceStamped.h tf2_msgs/TFMessage.h std_srvs/Empty.h
    diagnostic_msgs/DiagnosticArray.h)
  string(MAKE_C_IDENTIFIER ${_msg} _var)
  find_path(PGMCL_MSG_${_var} ${_msg})
  if(NOT PGMCL_MSG_${_var})
    list(APPEND _missing ${_msg})
  endif()
endforeach()
find_program(PGMCL_ROSMASTER rosmaster)
find_program(PGMCL_ROSBAG rosbag)
if(_missing)
  list(JOIN _missing ", " _missing)
  message(WARNING "pgmcl: PGMCL_WITH_ROS is ON but ROS 1 is incomplete (missing: ${_missing}); "
    "building without pgmcl_node and the rosbag I/O. `bash cmake/setup.sh` installs the "
    "Debian packages, or pass -DPGMCL_WITH_ROS=OFF to silence this.")
  return()
endif()
set(PGMCL_HAVE_ROS ON)
set(PGMCL_ROS_BUILT ON CACHE INTERNAL "The ROS 1 parts are built (cmake/demo.sh reads it)")
message(STATUS "pgmcl: ROS 1 found (roscpp ${PGMCL_ROSCPP_roscpp_VERSION}): building pgmcl_node "
  "and the rosbag I/O")

add_library(pgmcl_ros1_bag_deps INTERFACE)
target_include_directories(pgmcl_ros1_bag_deps SYSTEM INTERFACE ${PGMCL_ROSBAG_INCLUDE}
  ${PGMCL_PLUGINLIB_INCLUDE} ${PGMCL_CLASS_LOADER_INCLUDE} ${PGMCL_RCPPUTILS_INCLUDE}
  ${PGMCL_RCUTILS_INCLUDE} ${PGMCL_AMENT_INDEX_INCLUDE})
target_link_libraries(pgmcl_ros1_bag_deps INTERFACE ${PGMCL_ROSBAG_STORAGE_LIB}
  PkgConfig::PGMCL_ROSCPP)
add_library(pgmcl_ros1_node_deps INTERFACE)
target_link_libraries(pgmcl_ros1_node_deps INTERFACE PkgConfig::PGMCL_ROSCPP)
