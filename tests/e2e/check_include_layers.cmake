# Include layers: every source file may include project headers of its own layer or of a lower one only,
# so that the tree reads as the data flow (engine/README.md). Run by ctest:
#   cmake -DROOT=<source dir> -P tests/e2e/check_include_layers.cmake      checks the tree, fails on a violation
#   cmake -DSELF_TEST=<scratch dir> -P tests/e2e/check_include_layers.cmake plants violations in a scratch tree
#                                                                         and fails unless each is caught
# A file in a folder that has no layer is an error too: a new folder must be given its place below.

# Layers, lowest first. A path belongs to the longest prefix listed; equal numbers are one layer.
set(DAMPBENCH_LAYERS
  "engine/common"         0   # error type, key=value lists, random streams, statistics, tables, vector math
  "engine/record"         1   # records, units, derivatives, prepared signals
  "engine/model"          2   # model interface, metrics, bounds, parameter laws, law models
  "engine/kernels"        3   # SIMD lane kernels, CVODE reference
  "models"                4   # model families written with the kernels, their registry and fixtures
  "engine/evaluation"     5   # batches of candidates on records, sensitivity, bench workload
  "engine/control"        5   # the inverse of a damper model: the command for a desired force
  "engine/export"         5   # an identified model as C99 source
  "engine/structure"      5   # a building under an earthquake with a stepped damper, LQR gains
  "engine/identification" 6   # optimizer interface, lockstep repeated runs
  "optimizers"            7   # the algorithms and their registry
  "engine/lssvm"          8   # LS-SVM tunes its hyperparameters with an optimizer of the registry
  "datasets"              9   # generators of the synthetic grids (the sweep generates them on first use)
  "engine/fit"            10  # one fit from request to outcome: model by name, records, bounds, runs, evidence
  "engine/sweep"          11  # sweep files, scheduling, the results store, tables from it
  "engine/report"         12  # HTML reports from stores
  "engine/distributed"    13  # MPI and shards
  "engine/cli"            14  # the command line
  "python"                15  # the Python module, on the command line's library
  "bench"                 15
  "docs/extending"        15  # the examples of docs/extending.md
  "tests"                 16
)

# Sets ${out} to the layer number of a repository-relative path, or to "" when no prefix matches.
function(layer_of path out)
  set(best_len -1)
  set(best "")
  list(LENGTH DAMPBENCH_LAYERS n)
  math(EXPR last "${n} - 1")
  foreach(i RANGE 0 ${last} 2)
    math(EXPR j "${i} + 1")
    list(GET DAMPBENCH_LAYERS ${i} prefix)
    list(GET DAMPBENCH_LAYERS ${j} number)
    string(LENGTH "${prefix}" len)
    string(FIND "${path}/" "${prefix}/" at)
    if(at EQUAL 0 AND len GREATER best_len)
      set(best_len ${len})
      set(best ${number})
    endif()
  endforeach()
  set(${out} "${best}" PARENT_SCOPE)
endfunction()

# Appends to ${out} one message per violation found below root.
function(check_tree root out)
  set(problems "")
  file(GLOB_RECURSE sources RELATIVE "${root}"
    "${root}/engine/*.hpp" "${root}/engine/*.cpp" "${root}/models/*.hpp" "${root}/models/*.cpp"
    "${root}/optimizers/*.hpp" "${root}/optimizers/*.cpp" "${root}/datasets/*.hpp" "${root}/datasets/*.cpp"
    "${root}/bench/*.cpp" "${root}/python/*.hpp" "${root}/python/*.cpp" "${root}/docs/*.hpp" "${root}/docs/*.cpp" "${root}/tests/*.hpp" "${root}/tests/*.cpp")
  foreach(src IN LISTS sources)
    get_filename_component(dir "${src}" DIRECTORY)
    layer_of("${dir}" own)
    if(own STREQUAL "")
      list(APPEND problems "${src}: its folder has no layer (add it to tests/e2e/check_include_layers.cmake)")
      continue()
    endif()
    file(STRINGS "${root}/${src}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*" "\\1" target "${line}")
      get_filename_component(target_dir "${target}" DIRECTORY)
      layer_of("${target_dir}" theirs)
      if(theirs STREQUAL "")
        continue()  # not a project header (e.g. a file next to the includer)
      endif()
      if(theirs GREATER own)
        list(APPEND problems "${src} (layer ${own}) includes \"${target}\" (layer ${theirs}): against the data flow")
      endif()
    endforeach()
  endforeach()
  set(${out} "${problems}" PARENT_SCOPE)
endfunction()

if(DEFINED SELF_TEST)
  # A scratch tree with one downward include (allowed), one upward include and one file outside any layer.
  file(REMOVE_RECURSE "${SELF_TEST}")
  file(WRITE "${SELF_TEST}/engine/sweep/spec.hpp" "#include \"engine/record/dataset.hpp\"\n")
  file(WRITE "${SELF_TEST}/engine/record/dataset.hpp" "#pragma once\n")
  file(WRITE "${SELF_TEST}/engine/record/csv_loader.cpp" "#include <vector>\n#include \"engine/sweep/spec.hpp\"\n")
  file(WRITE "${SELF_TEST}/engine/stray.cpp" "int x;\n")
  check_tree("${SELF_TEST}" problems)
  list(LENGTH problems count)
  string(FIND "${problems}" "engine/record/csv_loader.cpp (layer 1) includes \"engine/sweep/spec.hpp\" (layer 11)" upward)
  string(FIND "${problems}" "engine/stray.cpp: its folder has no layer" stray)
  if(NOT count EQUAL 2 OR upward EQUAL -1 OR stray EQUAL -1)
    message(FATAL_ERROR "self-test: expected exactly the upward include and the stray file, got ${count}:\n${problems}")
  endif()
  message(STATUS "self-test: the upward include and the stray file were caught; the downward include passed")
  return()
endif()

if(NOT DEFINED ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<source dir> -P check_include_layers.cmake")
endif()
check_tree("${ROOT}" problems)
if(problems)
  list(JOIN problems "\n  " text)
  message(FATAL_ERROR "include layers violated:\n  ${text}")
endif()
message(STATUS "include layers: every project include points to its own layer or a lower one")
