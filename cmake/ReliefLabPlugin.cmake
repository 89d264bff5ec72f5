# relieflab_add_plugin(<target> SOURCES <cpp>... [GLSL <file>...])
#
# Builds a technique as a shared object that `relieflab --plugins DIR` loads
# (harness/technique/plugins.h). Its GLSL is embedded and registered when it loads, each file
# under the key plugins/<target>/<path relative to this CMakeLists.txt>: the name its
# intersect_file() returns. The sources include the harness's headers as "technique/...",
# "truth/..." (the layers a technique may use) and link the installed shared libraries, so the
# plugin shares the CLI's technique registry.
set(RELIEFLAB_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedFiles.cmake)

function(relieflab_add_plugin target)
  cmake_parse_arguments(arg "" "" "SOURCES;GLSL" ${ARGN})
  set(generated ${CMAKE_CURRENT_BINARY_DIR}/${target}_glsl.cpp)
  set(keys "")
  set(absolute "")
  foreach(f ${arg_GLSL})
    get_filename_component(abs ${f} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    file(RELATIVE_PATH rel ${CMAKE_CURRENT_SOURCE_DIR} ${abs})
    list(APPEND keys ${rel})
    list(APPEND absolute ${abs})
  endforeach()
  string(REPLACE ";" "|" key_list "${keys}")
  add_custom_command(
    OUTPUT ${generated}
    COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_CURRENT_SOURCE_DIR} -DOUTPUT=${generated}
            "-DFILES=${key_list}" -DORIGIN=${target} -DKEY_PREFIX=plugins/${target}/
            -P ${RELIEFLAB_EMBED_SCRIPT}
    DEPENDS ${absolute} ${RELIEFLAB_EMBED_SCRIPT}
    COMMENT "Embedding ${target}'s GLSL"
    VERBATIM)
  add_library(${target} MODULE ${arg_SOURCES} ${generated})
  target_link_libraries(${target} PRIVATE ReliefLab::technique ReliefLab::truth)
  target_compile_features(${target} PRIVATE cxx_std_20)
  # A plugin that references a symbol no ReliefLab library defines fails here, not at load.
  target_link_options(${target} PRIVATE LINKER:--no-undefined)
endfunction()
