# Writes ${CMAKE_BINARY_DIR}/generated/build_info.cc at every build (only touched when it
# changes), so report.json names the revision that was really built, not the one configured.
set(PQLAYOUT_BUILD_INFO_CC ${CMAKE_BINARY_DIR}/generated/build_info.cc)
add_custom_target(pqlayout_build_info
  COMMAND ${CMAKE_COMMAND}
    -DSOURCE_DIR=${CMAKE_SOURCE_DIR} -DOUTPUT=${PQLAYOUT_BUILD_INFO_CC}
    -DVERSION=${PROJECT_VERSION}
    -DLIBS=Ceres=${Ceres_VERSION},Eigen=${Eigen3_VERSION},CHOLMOD=${CHOLMOD_VERSION},OpenMesh=${OpenMesh_VERSION},CGAL=${CGAL_VERSION},yaml-cpp=${yaml-cpp_VERSION},glog=${glog_VERSION},nlohmann_json=${nlohmann_json_VERSION}
    -P ${CMAKE_SOURCE_DIR}/cmake/WriteBuildInfo.cmake
  BYPRODUCTS ${PQLAYOUT_BUILD_INFO_CC}
  COMMENT "" VERBATIM)
