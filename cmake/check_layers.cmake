# cmake -DLAYERS=<build>/pgmcl_layers.cmake -P cmake/check_layers.cmake
# The component graph must read common, sensor_model -> maps -> {map_io, sims, mcl} -> the
# edges: the simulator (the engine's test oracle) never links the engine, and the engine
# and the maps layer link no file-format library. A dependency outside a component's
# allowed list fails, naming both.
cmake_minimum_required(VERSION 3.22)
include(${LAYERS})
set(allowed_common "")
set(allowed_sensor_model "Eigen3::Eigen")
set(allowed_maps "pgmcl::sensor_model;pgmcl::common;OpenMP::OpenMP_CXX")
set(allowed_map_io "pgmcl::maps;yaml-cpp;PkgConfig::STB;ZLIB::ZLIB")
set(allowed_sims "pgmcl::maps;pgmcl::common;pgmcl::sensor_model;OpenMP::OpenMP_CXX")
set(allowed_mcl "pgmcl::maps;pgmcl::sensor_model;pgmcl::common;OpenMP::OpenMP_CXX")
set(allowed_nav "pgmcl::mcl")
set(allowed_io "pgmcl::common;pgmcl::sims;ZLIB::ZLIB")
set(allowed_eval "pgmcl::io")
set(allowed_replay "pgmcl::mcl;pgmcl::eval;pgmcl::io")
set(allowed_config "pgmcl::mcl;pgmcl::sims;pgmcl::map_io;pgmcl::io;yaml-cpp")
set(failed FALSE)
foreach(c IN LISTS components)
  foreach(d IN LISTS deps_${c})
    if(d MATCHES "^\\$<" OR d MATCHES "^-")  # build-only flags, sanitizers, warnings
      continue()
    endif()
    if(NOT d IN_LIST allowed_${c})
      message(SEND_ERROR "pgmcl::${c} links ${d}, which its layer may not use")
      set(failed TRUE)
    endif()
  endforeach()
endforeach()
if(NOT failed)
  message(STATUS "layers: ${components} link only what their layer allows")
endif()
