# One shared library per harness layer, whose headers only the layers above it can include.
#
#   relieflab_layer(<folder> [SOURCES <extra sources>...] [PUBLIC <libs>...] [PRIVATE <libs>...])
#
# builds harness/<folder>/*.cpp into relieflab_<folder>. Sources include headers as
# "<folder>/<file>.h" from a root; each layer has a root of its own in the build tree,
# ${RELIEFLAB_LAYER_ROOT}/<folder>, holding one link, <folder> -> harness/<folder>, and exposes
# it as a PUBLIC include directory. A target therefore sees exactly the roots of the layers it
# links (itself and those below): `#include "sweep/config.h"` in harness/core/ finds no file.
# --no-undefined makes a call into a layer it does not link fail at link time too.
set(RELIEFLAB_LAYER_ROOT ${CMAKE_BINARY_DIR}/layer_include)

function(relieflab_layer folder)
  cmake_parse_arguments(arg "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target relieflab_${folder})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/harness/${folder}/*.cpp)
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/harness/${folder}/*.h)
  add_library(${target} SHARED ${sources} ${arg_SOURCES})
  set(root ${RELIEFLAB_LAYER_ROOT}/${folder})
  file(MAKE_DIRECTORY ${root})
  if(NOT EXISTS ${root}/${folder})
    file(CREATE_LINK ${CMAKE_SOURCE_DIR}/harness/${folder} ${root}/${folder} SYMBOLIC)
  endif()
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${root}>
                                              $<INSTALL_INTERFACE:include/relieflab>)
  target_link_libraries(${target} PUBLIC ${arg_PUBLIC} PRIVATE ${arg_PRIVATE})
  target_link_options(${target} PRIVATE LINKER:--no-undefined)
  # -fPIC would otherwise forbid inlining a global function into its own file's callers
  # (it could be interposed), slowing the precomputes' inner loops.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  endif()
  set_target_properties(${target} PROPERTIES
    VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
    EXPORT_NAME ${folder} UNITY_BUILD ${RELIEFLAB_UNITY_BUILD})
  relieflab_warnings(${target})
  install(FILES ${headers} DESTINATION include/relieflab/${folder} COMPONENT devel)
  set_property(GLOBAL APPEND PROPERTY RELIEFLAB_LAYERS ${target})
endfunction()
