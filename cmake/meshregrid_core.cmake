# add_meshregrid_core(<name> SOURCES ... [DEPENDS ...])
# An algorithm core: a static library on VCGlib with no Qt or MeshLab dependency.
function(add_meshregrid_core name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC "${PROJECT_SOURCE_DIR}/filters")
  target_link_libraries(${name} PUBLIC vcglib_headers ${ARG_DEPENDS} PRIVATE meshregrid_warnings)
  # Position-independent (the cores go into plugins), but nothing interposes their
  # functions: calls within a core stay open to inlining.
  target_compile_options(${name} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
endfunction()
