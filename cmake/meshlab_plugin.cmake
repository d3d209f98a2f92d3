# Building MeshLab 2025.07 filter plugins out of tree: MeshLab's own headers,
# Qt5 with AUTOMOC, and the libmeshlab-common.so that the PyMeshLab wheel ships
# (double precision), so one binary loads in PyMeshLab and in MeshLab 2025.07d.
find_package(Qt5 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml Network)
find_package(GLEW REQUIRED)

if(NOT MESHLAB_COMMON_LIBRARY)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  execute_process(
    COMMAND "${Python3_EXECUTABLE}" -c "import importlib.util,os;s=importlib.util.find_spec('pymeshlab');print(os.path.join(os.path.dirname(s.origin),'lib','libmeshlab-common.so'))"
    OUTPUT_VARIABLE _common OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0 OR NOT EXISTS "${_common}")
    message(FATAL_ERROR "pymeshlab not found for ${Python3_EXECUTABLE}: run scripts/setup or set MESHLAB_COMMON_LIBRARY")
  endif()
  set(MESHLAB_COMMON_LIBRARY "${_common}" CACHE FILEPATH "libmeshlab-common.so of MeshLab 2025.07 (double)")
endif()

add_library(meshlab_common SHARED IMPORTED)
set_target_properties(meshlab_common PROPERTIES IMPORTED_LOCATION "${MESHLAB_COMMON_LIBRARY}")
target_include_directories(meshlab_common SYSTEM INTERFACE "${MESHLAB_SOURCE_DIR}/src")
target_compile_definitions(meshlab_common INTERFACE MESHLAB_VERSION=2025.07d MESHLAB_SCALAR=double)
target_link_libraries(meshlab_common INTERFACE vcglib_headers GLEW::GLEW
  Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml Qt5::Network)

set(MESHREGRID_PLUGIN_DIR "${PROJECT_BINARY_DIR}/plugins" CACHE INTERNAL "")

# add_meshregrid_plugin(<name> SOURCES ... CORES ...)
function(add_meshregrid_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;CORES" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES AUTOMOC ON PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY "${MESHREGRID_PLUGIN_DIR}"
    # No RPATH: the host (MeshLab or PyMeshLab) has already loaded libmeshlab-common and Qt.
    SKIP_BUILD_RPATH ON)
  target_include_directories(${name} PRIVATE "${PROJECT_SOURCE_DIR}/plugins")
  target_link_libraries(${name} PRIVATE meshlab_common ${ARG_CORES} meshregrid_warnings)
endfunction()
