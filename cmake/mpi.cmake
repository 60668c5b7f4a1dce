# DEB_MPI: the same deb, started by mpirun, spreads a study's budgets over
# the ranks (deb/distributed, docs/cluster.md). On when Debian's OpenMPI
# (libopenmpi-dev) is found; off in sanitizer and fuzz builds, whose checks
# are for deb's own code, not OpenMPI's.
if(DEB_SANITIZE OR DEB_FUZZ)
  set(DEB_MPI OFF)
else()
  find_package(MPI COMPONENTS CXX QUIET)
  if(MPI_CXX_FOUND)
    option(DEB_MPI "Build deb with MPI (mpirun -n P deb uncertainty ...)" ON)
  else()
    set(DEB_MPI OFF)
    message(STATUS "deb: OpenMPI (libopenmpi-dev) not found: deb is built without MPI; its test is skipped")
  endif()
endif()
