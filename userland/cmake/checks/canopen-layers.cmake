# SPDX-License-Identifier: GPL-2.0
# cmake -DLAYERS=<build>/canopen/canopen-layers.cmake -P canopen-layers.cmake
# The CANopen libraries are layers (docs/canopen.md, "Libraries"): every
# header of include/advee/canopen belongs to exactly one library; a file of
# a library includes CANopen headers of its own library or of the engine
# only (socketcan and cia402 are siblings); the engine includes no system
# I/O, thread or event header and reads no clock (time comes through NowFn;
# clock.hpp, which defines it, is the one exception).
cmake_minimum_required(VERSION 3.25)
include(${LAYERS})
set(problems "")

foreach(h IN LISTS ALL_HEADERS)
  set(n 0)
  foreach(layer ENGINE SOCKETCAN CIA402)
    if(h IN_LIST ${layer}_HEADERS)
      math(EXPR n "${n} + 1")
    endif()
  endforeach()
  if(NOT n EQUAL 1)
    string(APPEND problems "  include/advee/canopen/${h}: in ${n} libraries (userland/canopen/CMakeLists.txt lists each header once)\n")
  endif()
endforeach()

set(ENGINE_ALLOWED ${ENGINE_HEADERS})
set(SOCKETCAN_ALLOWED ${ENGINE_HEADERS} ${SOCKETCAN_HEADERS})
set(CIA402_ALLOWED ${ENGINE_HEADERS} ${CIA402_HEADERS})
# What the engine must not include: sockets, descriptors, polling, timers,
# threads, the helpers that wrap them.
set(ENGINE_FORBIDDEN "^(sys/.*|linux/.*|net/.*|poll\\.h|unistd\\.h|fcntl\\.h|signal\\.h|csignal|thread|mutex|condition_variable|future|atomic|advee/unique_fd\\.hpp|advee/throw_errno\\.hpp)$")

foreach(layer ENGINE SOCKETCAN CIA402)
  set(files ${${layer}_SOURCES})
  foreach(h IN LISTS ${layer}_HEADERS)
    list(APPEND files ${INCLUDE_DIR}/${h})
  endforeach()
  string(TOLOWER ${layer} lname)
  foreach(f IN LISTS files)
    file(STRINGS ${f} includes REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS includes)
      if(NOT line MATCHES "#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"]")
        continue()
      endif()
      set(inc ${CMAKE_MATCH_1})
      if(inc MATCHES "^advee/canopen/(.+)$")
        if(NOT CMAKE_MATCH_1 IN_LIST ${layer}_ALLOWED)
          string(APPEND problems "  ${f}: library ${lname} includes ${inc} of another layer\n")
        endif()
      elseif(layer STREQUAL "ENGINE" AND inc MATCHES "${ENGINE_FORBIDDEN}")
        string(APPEND problems "  ${f}: the engine includes <${inc}> (no I/O, no threads)\n")
      endif()
    endforeach()
    if(layer STREQUAL "ENGINE" AND NOT f MATCHES "/clock\\.hpp$")
      file(STRINGS ${f} reads REGEX "(steady_clock|SteadyClock)::now")
      if(reads)
        string(APPEND problems "  ${f}: the engine reads the monotonic clock (use the injected NowFn)\n")
      endif()
    endif()
  endforeach()
endforeach()

if(problems)
  message(FATAL_ERROR "CANopen layering broken:\n${problems}")
endif()
message(STATUS "CANopen layers: every header in one library, no include across layers")
