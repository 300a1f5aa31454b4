# Fails if any source file under DIR includes a header matching the regular expression PATTERN;
# WHAT names the forbidden dependency in the messages. Keeps the layering of the libraries:
# dem/ knows nothing of deal.II, fem/ nothing of particles (they meet only in coupling/).
# With -DTOP_LEVEL_ONLY=ON, only the files directly in DIR, not in its subfolders: the DEM engine
# (dem/) is checked without its I/O (dem/io/) and laboratory (dem/laboratory/) libraries.
if(TOP_LEVEL_ONLY)
  file(GLOB sources "${DIR}/*.h" "${DIR}/*.cc")
else()
  file(GLOB_RECURSE sources "${DIR}/*.h" "${DIR}/*.cc")
endif()
foreach(f ${sources})
  file(STRINGS "${f}" hits REGEX "#include *[<\"]${PATTERN}")
  if(hits)
    message(FATAL_ERROR "${f} includes ${WHAT}: ${hits}")
  endif()
endforeach()
list(LENGTH sources n)
message(STATUS "checked ${n} files of ${DIR}: no include of ${WHAT}")
