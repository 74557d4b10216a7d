# The README's "As a library" example, built as a user would: install whatnext into a prefix, then
# configure and build this folder's project against it with a plain find_package(whatnext), and
# run it. Also checks that README.md shows exactly these two files.
# cmake -DSOURCE=<repo> -DBUILD=<build dir> -DWORK=<scratch dir> -DCLI=<whatnext> -DGENERATOR=<g>
#       -DCXX=<compiler> -P check.cmake
cmake_minimum_required(VERSION 3.20)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

# README.md's code blocks under "## As a library" are this project's files.
file(READ ${SOURCE}/README.md readme)
string(FIND "${readme}" "## As a library" at)
string(SUBSTRING "${readme}" ${at} -1 section)
foreach(pair "cmake;CMakeLists.txt" "cpp;my_machine.cpp")
  list(GET pair 0 lang)
  list(GET pair 1 file)
  string(FIND "${section}" "```${lang}\n" start)
  if(start LESS 0)
    message(FATAL_ERROR "README.md: no ```${lang} block under '## As a library'")
  endif()
  string(LENGTH "```${lang}\n" n)
  math(EXPR start "${start} + ${n}")
  string(SUBSTRING "${section}" ${start} -1 rest)
  string(FIND "${rest}" "```" end)
  string(SUBSTRING "${rest}" 0 ${end} shown)
  file(READ ${SOURCE}/tests/consumer/${file} actual)
  if(NOT shown STREQUAL actual)
    message(FATAL_ERROR "README.md's ```${lang} block under '## As a library' differs from tests/consumer/${file}")
  endif()
endforeach()

file(REMOVE_RECURSE ${WORK})
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE}/tests/consumer -B ${WORK}/build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK}/prefix)
run(${CMAKE_COMMAND} --build ${WORK}/build)
run(${WORK}/build/my_machine)
set(program "${out}")
# The library gives the command's answer for the same machine.
run(${CLI} run --example 2 --set geometry.rope_length=0.7 -q)
string(STRIP "${out}" sentence)
string(FIND "${program}" "${sentence}\n" found)
if(found LESS 0 OR sentence STREQUAL "")
  message(FATAL_ERROR "my_machine printed\n${program}\nbut whatnext run says '${sentence}'")
endif()
message(STATUS "my_machine, built against the installed whatnext:\n${program}")
