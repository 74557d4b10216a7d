# The sources in the project's style (.clang-format): clang-format --dry-run --Werror over every C
# and C++ file of the tree, one test. Run as cmake -DSOURCE=<tree> -DCLANG_FORMAT=<program> -P.
file(GLOB_RECURSE sources LIST_DIRECTORIES false
     ${SOURCE}/src/*.cpp ${SOURCE}/src/*.hpp ${SOURCE}/include/*.hpp ${SOURCE}/apps/*.cpp ${SOURCE}/apps/*.hpp
     ${SOURCE}/tests/*.cpp ${SOURCE}/tests/*.hpp ${SOURCE}/python/src/*.cpp ${SOURCE}/web/wasm/*.cpp ${SOURCE}/web/wasm/*.hpp
     ${SOURCE}/bench/*.cpp ${SOURCE}/bench/*.c ${SOURCE}/fuzz/*.cpp)
list(LENGTH sources count)
if(count LESS 50)
  message(FATAL_ERROR "format check: only ${count} sources found under ${SOURCE}")
endif()
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${sources} RESULT_VARIABLE failed
                ERROR_VARIABLE complaints)
if(failed)
  message(FATAL_ERROR "${complaints}format check: the lines above differ from .clang-format's style; "
                      "clang-format -i FILE fixes them")
endif()
message(STATUS "format check: ${count} sources in .clang-format's style")
