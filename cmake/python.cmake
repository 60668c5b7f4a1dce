# DEB_PYTHON: build the Python module deb (python/, docs/python.md) into
# build/python. On by default when Python 3 (interpreter, headers, NumPy) and
# pybind11 are found; without them it is off, with a message, and the rest of
# deb builds as before. Never in the sanitizer or fuzzing builds: a module
# loaded into an uninstrumented python3 cannot carry ASan's runtime.
#
# Debian's python3 (python3-dev, python3-numpy, pybind11-dev): another
# python3 earlier in PATH (pyenv, a virtualenv) has neither Debian's NumPy
# nor, usually, the same version as the headers pybind11 finds.
if(DEB_SANITIZE OR DEB_FUZZ)
  message(STATUS "deb: no Python module in a DEB_SANITIZE or DEB_FUZZ build (docs/python.md)")
  set(DEB_PYTHON OFF)
  return()
endif()
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module NumPy QUIET)
if(Python3_FOUND)
  find_package(pybind11 CONFIG QUIET)
endif()
if(Python3_FOUND AND pybind11_FOUND)
  option(DEB_PYTHON "Build the Python module deb (python/)" ON)
else()
  # Not cached: a later configure that finds them (tools/check after
  # tools/quickstart installed fewer packages) turns the module on.
  message(STATUS "deb: no Python module (needs python3-dev, python3-numpy and pybind11-dev: tools/install-deps)")
  set(DEB_PYTHON OFF)
endif()
