# Writes the source revision into a generated source on every build, so that
# summary.json names the exact code a result came from.
set(COSIM_REVISION_CPP ${CMAKE_BINARY_DIR}/generated/revision.cpp)
add_custom_target(cosim_revision ALL
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DOUTPUT=${COSIM_REVISION_CPP}
          -P ${CMAKE_SOURCE_DIR}/cmake/write_revision.cmake
  BYPRODUCTS ${COSIM_REVISION_CPP}
  COMMENT "Recording source revision")
