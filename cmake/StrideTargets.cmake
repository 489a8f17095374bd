# Helpers shared by every Stride target: warning flags and the library layout convention
# (public headers in <area>/include/stride/<area>/, sources in <area>/src/).

add_library(stride_warnings INTERFACE)
target_compile_options(stride_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
  -Wimplicit-fallthrough $<$<BOOL:${STRIDE_WERROR}>:-Werror>
  # GCC 12 reports false -Wrestrict/-Wstringop-overflow in libstdc++'s std::string at -O2/-O3
  # (GCC bugs 105329, 105651); they are not in project code.
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict -Wno-stringop-overflow>)

# stride_add_library(<target> [DEPS ...] [PRIVATE_DEPS ...])
# Builds every .cpp under src/ of the current folder into a static library whose public
# headers live under include/.
function(stride_add_library target)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS;SOURCE_DIRS;EXCLUDE_DIRS" ${ARGN})
  # The sources under src/ (or under src/<dir>/ for each of SOURCE_DIRS), less EXCLUDE_DIRS.
  set(sources)
  if(ARG_SOURCE_DIRS)
    foreach(dir ${ARG_SOURCE_DIRS})
      file(GLOB_RECURSE dir_sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/${dir}/*.cpp")
      list(APPEND sources ${dir_sources})
    endforeach()
  else()
    file(GLOB_RECURSE sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp")
  endif()
  foreach(dir ${ARG_EXCLUDE_DIRS})
    list(FILTER sources EXCLUDE REGEX "^${CMAKE_CURRENT_SOURCE_DIR}/src/${dir}/")
  endforeach()
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  target_link_libraries(${target} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS} stride_warnings)
endfunction()
