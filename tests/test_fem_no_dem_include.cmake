# Fails if any source file under DIR (fem/) includes a header of the DEM (dem/): the continuum
# only meets particles through coupling/.
file(GLOB_RECURSE sources "${DIR}/*.h" "${DIR}/*.cc")
foreach(f ${sources})
  file(STRINGS "${f}" hits REGEX "#include *[<\"](dem/|\\.\\./dem/)")
  if(hits)
    message(FATAL_ERROR "${f} includes the DEM: ${hits}")
  endif()
endforeach()
list(LENGTH sources n)
message(STATUS "checked ${n} files of ${DIR}: no dem/ include")
