# Finds ARPACK (arpack-ng, Debian: libarpack2-dev) with the LAPACK/BLAS it needs.
# Defines the imported target ARPACK::ARPACK. ARPACK has a Fortran interface only; the
# project declares the few routines it calls itself.
find_library(ARPACK_LIBRARY arpack)
find_package(LAPACK REQUIRED)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(ARPACK REQUIRED_VARS ARPACK_LIBRARY)
if(ARPACK_FOUND AND NOT TARGET ARPACK::ARPACK)
  add_library(ARPACK::ARPACK UNKNOWN IMPORTED)
  set_target_properties(ARPACK::ARPACK PROPERTIES
    IMPORTED_LOCATION "${ARPACK_LIBRARY}"
    INTERFACE_LINK_LIBRARIES "${LAPACK_LIBRARIES}")
endif()
mark_as_advanced(ARPACK_LIBRARY)
