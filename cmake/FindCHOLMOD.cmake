# Finds CHOLMOD from Debian's libsuitesparse-dev (SuiteSparse 5.12 ships no CMake config).
# Defines the imported target SuiteSparse::CHOLMOD and CHOLMOD_VERSION.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
find_library(AMD_LIBRARY amd)
find_library(CAMD_LIBRARY camd)
find_library(COLAMD_LIBRARY colamd)
find_library(CCOLAMD_LIBRARY ccolamd)
if(CHOLMOD_INCLUDE_DIR AND EXISTS "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h")
  file(STRINGS "${CHOLMOD_INCLUDE_DIR}/cholmod_core.h" _v REGEX "#define CHOLMOD_(MAIN|SUB|SUBSUB)_VERSION")
  string(REGEX REPLACE ".*MAIN_VERSION ([0-9]+).*SUB_VERSION ([0-9]+).*SUBSUB_VERSION ([0-9]+).*"
         "\\1.\\2.\\3" CHOLMOD_VERSION "${_v}")
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR SUITESPARSE_CONFIG_LIBRARY AMD_LIBRARY COLAMD_LIBRARY
  VERSION_VAR CHOLMOD_VERSION)
if(CHOLMOD_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES
      "${AMD_LIBRARY};${CAMD_LIBRARY};${COLAMD_LIBRARY};${CCOLAMD_LIBRARY};${SUITESPARSE_CONFIG_LIBRARY}")
endif()
