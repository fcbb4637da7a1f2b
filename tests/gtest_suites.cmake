# SPDX-License-Identifier: GPL-3.0-or-later
# roifem_gtest_suites(TARGET [ALONE test...] [SLOW test...] [TIMEOUT seconds])
#
# One ctest entry per gtest suite of TARGET, named after the suite, each one process that runs the
# whole suite: a test binary linked with some 150 shared libraries (Gmsh, OpenCASCADE, PETSc) takes
# 0.2-0.35 s to start, more under the sanitizers, and one process a test paid that 400 times.
# gtest still names each failing test in the entry's output (ctest --output-on-failure).
#
# The suites are read from TARGET's sources: TEST(Suite, ...), TEST_F(Suite, ...) and TEST_P(Suite,
# ...) at the start of a line (a parameterized suite's tests are Prefix/Suite.Name/Param). A test
# named in ALONE (Suite.Name) gets an entry of its own under that name, and its suite's entry leaves
# it out: one that must not share a process, or a long one. A test named in SLOW is such an entry
# with the label "slow": the sanitized phase leaves it to Release (docs/testing.md).
function(roifem_gtest_suites target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "TIMEOUT" "ALONE;SLOW")
  if(NOT arg_TIMEOUT)
    set(arg_TIMEOUT 600)
  endif()
  get_target_property(sources ${target} SOURCES)
  set(plain "")
  set(parameterized "")
  foreach(source IN LISTS sources)
    if(NOT IS_ABSOLUTE ${source})
      set(source ${CMAKE_CURRENT_SOURCE_DIR}/${source})
    endif()
    if(NOT source MATCHES "\\.cpp$")
      continue()
    endif()
    # A suite added to a source must reach its entry: the build re-runs CMake when a source changes.
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${source})
    file(STRINGS ${source} declarations REGEX "^TEST(_F|_P)?\\(")
    foreach(line IN LISTS declarations)
      if(line MATCHES "^TEST(_F|_P)?\\(([A-Za-z0-9_]+),")
        if(CMAKE_MATCH_1 STREQUAL "_P")
          list(APPEND parameterized ${CMAKE_MATCH_2})
        else()
          list(APPEND plain ${CMAKE_MATCH_2})
        endif()
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES plain)
  list(REMOVE_DUPLICATES parameterized)
  foreach(suite IN LISTS plain parameterized)
    if(suite IN_LIST parameterized)
      set(filter "*/${suite}.*")
    else()
      set(filter "${suite}.*")
    endif()
    set(left_out "")
    foreach(test IN LISTS arg_ALONE arg_SLOW)
      if(test MATCHES "^${suite}\\.")
        list(APPEND left_out ${test})
      endif()
    endforeach()
    if(left_out)
      list(JOIN left_out ":" negative)
      string(APPEND filter "-${negative}")
    endif()
    add_test(NAME ${suite} COMMAND ${target} --gtest_filter=${filter})
    set_tests_properties(${suite} PROPERTIES TIMEOUT ${arg_TIMEOUT} LABELS gtest)
  endforeach()
  foreach(test IN LISTS arg_ALONE)
    add_test(NAME ${test} COMMAND ${target} --gtest_filter=${test})
    set_tests_properties(${test} PROPERTIES TIMEOUT ${arg_TIMEOUT} LABELS gtest)
  endforeach()
  foreach(test IN LISTS arg_SLOW)
    add_test(NAME ${test} COMMAND ${target} --gtest_filter=${test})
    set_tests_properties(${test} PROPERTIES TIMEOUT ${arg_TIMEOUT} LABELS "gtest;slow")
  endforeach()
  # The check that no suite was missed (a declaration this reading did not see would never run):
  # the binary's own list of suites against the entries'; and that each test named alone exists (a
  # filter that matches nothing runs nothing, and passes).
  list(JOIN plain " " plain_words)
  list(JOIN parameterized " " parameterized_words)
  list(JOIN arg_ALONE " " alone_words)
  list(JOIN arg_SLOW " " slow_words)
  add_test(NAME ${target}.every_suite_has_an_entry
           COMMAND sh -c "$<TARGET_FILE:${target}> --gtest_list_tests > \"$1.list\" && \
                          grep -E '^[A-Za-z0-9_/]+[.]$' \"$1.list\" | sed -e 's/\\.$//' -e 's#.*/##' | sort -u > \"$1\" && \
                          for s in ${plain_words} ${parameterized_words}; do echo $s; done | sort -u | diff \"$1\" - && \
                          awk '/^[^ ]/ { suite = $1 } /^  / { print suite $1 }' \"$1.list\" > \"$1.tests\" && \
                          for t in ${alone_words} ${slow_words}; do \
                            grep -qxF $t \"$1.tests\" || { echo \"no test $t\"; exit 1; }; \
                          done && echo 'every suite has an entry'"
                   sh ${CMAKE_CURRENT_BINARY_DIR}/${target}_suites.txt)
  set_tests_properties(${target}.every_suite_has_an_entry PROPERTIES PASS_REGULAR_EXPRESSION "every suite has an entry" LABELS gtest)
endfunction()
