# Which interpreter the Python module is built and tested for, and whether
# it is built at all (METRICA_BUILD_PYTHON: AUTO, ON or OFF).
#
# The interpreter given with -DPython3_EXECUTABLE=..., else the first of
# `python3` on PATH and Debian's /usr/bin/python3 that imports numpy and
# has Python's headers (a pyenv, conda or venv interpreter often has
# neither numpy nor the system's packages). The choice is made again at
# every configure, so a changed PATH is followed; pybind11's CMake package
# (Debian's pybind11-dev) must be found too. With AUTO and no such
# interpreter the module is left out with one line; ON makes that an error.
#
# Sets METRICA_PYTHON (ON when the module is built) and, when it is,
# Python3_EXECUTABLE for find_package(Python3).
set(METRICA_BUILD_PYTHON AUTO CACHE STRING
    "Build the Python module: AUTO (when an interpreter with numpy, Python's headers and pybind11 is found), ON, OFF")
set_property(CACHE METRICA_BUILD_PYTHON PROPERTY STRINGS AUTO ON OFF)
string(TOUPPER "${METRICA_BUILD_PYTHON}" metrica_python_mode)
if(metrica_python_mode MATCHES "^(1|YES|TRUE|Y)$")
  set(metrica_python_mode ON)
elseif(metrica_python_mode MATCHES "^(0|NO|FALSE|N)$")
  set(metrica_python_mode OFF)
endif()
if(NOT metrica_python_mode MATCHES "^(AUTO|ON|OFF)$")
  message(FATAL_ERROR "METRICA_BUILD_PYTHON is AUTO, ON or OFF (got '${METRICA_BUILD_PYTHON}')")
endif()

set(METRICA_PYTHON OFF)
if(NOT metrica_python_mode STREQUAL "OFF")
  if(DEFINED CACHE{Python3_EXECUTABLE})
    set(candidates "${Python3_EXECUTABLE}")
  else()
    find_program(python_on_path NAMES python3 NO_CACHE)
    set(candidates ${python_on_path})
    if(EXISTS /usr/bin/python3)
      list(APPEND candidates /usr/bin/python3)
    endif()
    list(REMOVE_DUPLICATES candidates)
  endif()
  set(why "")
  set(chosen "")
  foreach(candidate IN LISTS candidates)
    # 0: numpy and Python.h; 3: numpy without the headers; else no numpy.
    execute_process(
      COMMAND "${candidate}" -c "import os, sys, sysconfig, numpy; sys.exit(0 if os.path.exists(os.path.join(sysconfig.get_paths()['include'], 'Python.h')) else 3)"
      RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
    if(status STREQUAL "0")
      set(chosen "${candidate}")
      break()
    elseif(status STREQUAL "3")
      list(APPEND why "${candidate} has no Python.h (python3-dev)")
    else()
      list(APPEND why "${candidate} cannot import numpy")
    endif()
  endforeach()
  if(NOT candidates)
    list(APPEND why "no python3 found")
  endif()
  if(chosen)
    # Python first, so that pybind11's package takes this interpreter.
    set(Python3_EXECUTABLE "${chosen}")
    find_package(Python3 COMPONENTS Interpreter Development.Module)
    find_package(pybind11 2.6 CONFIG QUIET)
    if(NOT Python3_FOUND)
      list(APPEND why "CMake's FindPython3 did not take ${chosen}")
      set(chosen "")
    elseif(NOT pybind11_FOUND)
      list(APPEND why "pybind11's CMake package not found (pybind11-dev)")
      set(chosen "")
    endif()
  endif()
  if(chosen)
    set(METRICA_PYTHON ON)
    message(STATUS "Metrica: the Python module is built for ${chosen}")
  else()
    unset(Python3_EXECUTABLE)
    string(REPLACE ";" "; " why "${why}")
    string(CONCAT message "the Python module is left out: ${why}. scripts/setup installs python3-numpy, "
                          "python3-dev and pybind11-dev; -DPython3_EXECUTABLE=... chooses another interpreter")
    if(metrica_python_mode STREQUAL "ON")
      message(FATAL_ERROR "Metrica: ${message}; or -DMETRICA_BUILD_PYTHON=OFF")
    endif()
    message(STATUS "Metrica: ${message}")
  endif()
endif()
