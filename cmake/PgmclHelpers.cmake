# Shared compile settings and the one-folder-one-target helper.

add_library(pgmcl_warnings INTERFACE)
target_compile_options(pgmcl_warnings INTERFACE -Wall -Wextra -Wpedantic
  $<$<BOOL:${PGMCL_WERROR}>:-Werror>)

add_library(pgmcl_sanitizers INTERFACE)
if(PGMCL_SANITIZE)
  target_compile_options(pgmcl_sanitizers INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(pgmcl_sanitizers INTERFACE -fsanitize=address,undefined)
endif()

# pgmcl_add_component(<name> [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Builds <name>/src/*.cpp into the static library pgmcl_<name>, exported as
# pgmcl::<name>, with public headers under <name>/include/pgmcl/<name>/.
function(pgmcl_add_component name)
  cmake_parse_arguments(ARG "" "" "PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  file(GLOB_RECURSE srcs CONFIGURE_DEPENDS ${dir}/src/*.cpp)
  add_library(pgmcl_${name} STATIC ${srcs})
  add_library(pgmcl::${name} ALIAS pgmcl_${name})
  set_target_properties(pgmcl_${name} PROPERTIES EXPORT_NAME ${name}
    POSITION_INDEPENDENT_CODE ON)
  target_include_directories(pgmcl_${name} PUBLIC
    $<BUILD_INTERFACE:${dir}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(pgmcl_${name} PUBLIC cxx_std_20)
  target_link_libraries(pgmcl_${name} PUBLIC ${ARG_PUBLIC_DEPS}
    PRIVATE ${ARG_PRIVATE_DEPS} $<BUILD_INTERFACE:pgmcl_warnings>)
  if(PGMCL_SANITIZE)
    target_link_libraries(pgmcl_${name} PUBLIC $<BUILD_INTERFACE:pgmcl_sanitizers>)
  endif()
  set_property(GLOBAL APPEND PROPERTY PGMCL_COMPONENTS ${name})
  install(DIRECTORY ${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# Link OpenMP when we have it; the code guards its pragmas with _OPENMP.
function(pgmcl_use_openmp target)
  if(PGMCL_HAVE_OPENMP)
    target_link_libraries(${target} PUBLIC OpenMP::OpenMP_CXX)
  endif()
endfunction()
