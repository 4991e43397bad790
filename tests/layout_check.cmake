# Checks that the library's parts depend on each other one way only, and that GL, CGAL and
# Embree headers stay where the README's layout table says they are.
# Run as: cmake -DSOURCE_DIR=<repo> -P tests/layout_check.cmake (CTest does).
#   cli -> registry -> {gl_methods, reference_cgal, reference_embree} -> representations -> formats -> core
#   gl_methods -> gl -> core;  cli -> pictures -> {gl, formats};  cli -> html -> formats;
#   cli -> reconstruction -> core;  cli -> mpeg -> core;  cli -> streaming -> formats;
#   cli -> measurement -> {protocols, mpeg, streaming, gl_methods, reference_embree};
#   protocols -> {reconstruction, representations}
cmake_minimum_required(VERSION 3.22)

# The parts of roving/ each part may include (itself included).
set(allowed_core core)
set(allowed_formats core formats)
set(allowed_representations core formats representations)
set(allowed_gl core gl)
set(allowed_pictures core formats gl pictures)
set(allowed_html core formats html)
set(allowed_gl_methods core formats representations gl gl_methods)
# The references' headers are installed as roving/reference_cgal/ and roving/reference_embree/.
set(allowed_registry core formats representations gl gl_methods registry reference_cgal reference_embree)
set(allowed_reconstruction core reconstruction)
set(allowed_mpeg core mpeg)
set(allowed_protocols core formats representations reconstruction protocols)
set(allowed_streaming core formats streaming)
set(allowed_measurement core formats representations gl gl_methods reconstruction mpeg protocols streaming measurement reference_embree)
set(allowed_cli core formats representations gl gl_methods registry pictures html reconstruction mpeg protocols streaming measurement cli reference_cgal reference_embree)
set(allowed_reference_cgal core formats representations reference_cgal)
set(allowed_reference_embree core formats representations reference_embree)

set(violations "")
macro(violation file line why)
  string(APPEND violations "  ${file}: ${line}  (${why})\n")
endmacro()

file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}"
  "${SOURCE_DIR}/roving/*.h" "${SOURCE_DIR}/roving/*.cpp"
  "${SOURCE_DIR}/reference_cgal/*.h" "${SOURCE_DIR}/reference_cgal/*.cpp"
  "${SOURCE_DIR}/reference_embree/*.h" "${SOURCE_DIR}/reference_embree/*.cpp"
  "${SOURCE_DIR}/datasets_gen/*.h" "${SOURCE_DIR}/datasets_gen/*.cpp"
  "${SOURCE_DIR}/bench/*.h" "${SOURCE_DIR}/bench/*.cpp"
  "${SOURCE_DIR}/tests/*.h" "${SOURCE_DIR}/tests/*.cpp")
list(LENGTH sources count)
if(count LESS 20)
  message(FATAL_ERROR "layout check: found only ${count} sources under ${SOURCE_DIR}; wrong SOURCE_DIR?")
endif()

foreach(file IN LISTS sources)
  # The part a file belongs to: roving/<part>/..., or a top-level folder.
  if(file MATCHES "^roving/([a-z_]+)/")
    set(part "${CMAKE_MATCH_1}")
  elseif(file MATCHES "^(reference_cgal|reference_embree)/")
    set(part "${CMAKE_MATCH_1}")
  else()
    set(part "")  # datasets_gen, bench, tests: programs on top, may include any part
  endif()
  file(STRINGS "${SOURCE_DIR}/${file}" includes REGEX "^#include")
  foreach(line IN LISTS includes)
    if(part AND line MATCHES "\"roving/([a-z_]+)/")
      if(NOT DEFINED allowed_${part})
        violation("${file}" "${line}" "roving/${part}/ is not a known part")
      else()
        list(FIND allowed_${part} "${CMAKE_MATCH_1}" found)
        if(found EQUAL -1)
          violation("${file}" "${line}" "${part} may not depend on ${CMAKE_MATCH_1}")
        endif()
      endif()
    endif()
    if(line MATCHES "<(GL|EGL|GLES[0-9]*)/" AND NOT file MATCHES "^roving/gl/")
      violation("${file}" "${line}" "GL, OSMesa and EGL headers stay in roving/gl/")
    endif()
    if(line MATCHES "<embree[0-9]*/" AND NOT file MATCHES "^reference_embree/[^/]*\\.(cpp|h)$")
      violation("${file}" "${line}" "Embree headers stay in reference_embree's own files (not its installed headers)")
    endif()
    # CGAL: the reference, the dataset generator's voxeliser, point-cloud normals and surfel radii
    # (PCA and MST orientation, which the loader needs below the references), and the certified
    # shares' triangle-to-triangle distance (beside Embree's BVH).
    if(line MATCHES "<CGAL/" AND NOT file MATCHES "^(reference_cgal/[^/]*\\.(cpp|h)|(datasets_gen/voxelize|roving/representations/point_normals|roving/representations/surfels|reference_embree/certified_area_within)\\.cpp)$")
      violation("${file}" "${line}" "CGAL headers stay in reference_cgal's own files (not its installed headers)")
    endif()
  endforeach()
endforeach()

if(violations)
  message(FATAL_ERROR "layout check failed:\n${violations}")
endif()
message(STATUS "layout check: ${count} files, every include goes one way")
