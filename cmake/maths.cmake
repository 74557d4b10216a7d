# The maths library of every native build: the very musl sources that Emscripten compiles into the
# page's WebAssembly, from Debian's emscripten package, so that the command, the Python module and
# the page compute sin, cos, pow... to the same bits. With the C library's own libm the page's map
# differed from `whatnext sweep` in last digits, and glibc picks its FMA or AVX2 variants by the
# CPU at run time, so two x86 machines could differ too (docs/architecture.md, "One maths library").
#
# whatnext_maths is an object library whose objects go into whatnext_core (and the whatnext program,
# which compiles the library's sources itself): every binary that has the core has them, whatever
# the order of its link line. Its symbols are hidden: they bind inside our binaries and the Python
# module and never stand in for the libm of a program that loads us.
find_path(WHATNEXT_MUSL_DIR src/math/pow.c
  PATHS /usr/share/emscripten/system/lib/libc/musl /usr/lib/emscripten/system/lib/libc/musl
  NO_DEFAULT_PATH
  DOC "Emscripten's musl (Debian: emscripten), whose maths every native build uses")
if(NOT WHATNEXT_MUSL_DIR)
  message(FATAL_ERROR "the maths library is Emscripten's musl: install Debian's emscripten package "
                      "(scripts/install-deps.sh), or set WHATNEXT_MUSL_DIR to its system/lib/libc/musl")
endif()

# The C compiler of the C++ one (clang-14 beside clang++-14) unless CC names another: one compiler
# for the whole build, whose sanitizer and fuzzer flags (WHATNEXT_SANITIZE, WHATNEXT_FUZZ) it knows.
if(NOT CMAKE_C_COMPILER AND NOT DEFINED ENV{CC} AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  string(REGEX REPLACE "clang\\+\\+([^/]*)$" "clang\\1" c_compiler "${CMAKE_CXX_COMPILER}")
  if(EXISTS "${c_compiler}")
    set(CMAKE_C_COMPILER "${c_compiler}")
  endif()
endif()
enable_language(C)
if(CMAKE_CXX_COMPILER_LAUNCHER AND NOT CMAKE_C_COMPILER_LAUNCHER)
  set(CMAKE_C_COMPILER_LAUNCHER ${CMAKE_CXX_COMPILER_LAUNCHER})
endif()

# The functions the library calls (sin, cos, tan, atan2, asin, acos, hypot, pow, log, log10),
# sincos, into which the compiler merges a sin and a cos of one angle, and exp and exp2, which it
# may make of pow(e, x) and pow(2, x); with the helpers they call. Emscripten takes pow.c and log.c,
# not pow_small.c and log_small.c, for a link at -O2 as web/wasm's (its tools/system_libs.py);
# sqrt, fma, floor and the like are correctly rounded in any C library and stay the system's.
set(WHATNEXT_MUSL_FUNCTIONS sin cos tan atan atan2 asin acos hypot pow log log10 sincos exp exp2)
set(WHATNEXT_MUSL_SOURCES)
foreach(name ${WHATNEXT_MUSL_FUNCTIONS} __sin __cos __tan __rem_pio2 __rem_pio2_large
             exp_data log_data pow_data __math_invalid __math_divzero __math_oflow __math_uflow
             __math_xflow)
  list(APPEND WHATNEXT_MUSL_SOURCES ${WHATNEXT_MUSL_DIR}/src/math/${name}.c)
endforeach()
add_library(whatnext_maths OBJECT ${WHATNEXT_MUSL_SOURCES})
# Compiled against musl's own headers, as Emscripten does (its arch/emscripten types are the
# compiler's own: __PTRDIFF_TYPE__, __INT64_TYPE__), not the system's: glibc's math.h declares
# musl's internal __sin and __cos with other types.
target_compile_options(whatnext_maths PRIVATE -nostdinc)
target_include_directories(whatnext_maths SYSTEM PRIVATE ${WHATNEXT_MUSL_DIR}/include
                           ${WHATNEXT_MUSL_DIR}/arch/emscripten ${WHATNEXT_MUSL_DIR}/arch/generic)
target_include_directories(whatnext_maths PRIVATE ${WHATNEXT_MUSL_DIR}/src/include
                           ${WHATNEXT_MUSL_DIR}/src/internal)
# As Emscripten compiles its libc (-fno-builtin), and no contraction into fused multiply-adds,
# which WebAssembly has not: each operation rounded on its own, as in the page.
target_compile_options(whatnext_maths PRIVATE -O2 -fno-builtin -ffp-contract=off -fno-fast-math
                       -fvisibility=hidden -w)
# musl is the C library's code, not ours to sanitize (its bit twiddling shifts negative numbers).
if(WHATNEXT_SANITIZE)
  target_compile_options(whatnext_maths PRIVATE -fno-sanitize=all)
endif()
set_target_properties(whatnext_maths PROPERTIES POSITION_INDEPENDENT_CODE ON C_STANDARD 99
                      C_EXTENSIONS ON)


# The library's own arithmetic likewise, in every native target from here on: no a * b + c fused
# into one rounding where the processor has an FMA (an ARM64 build, or -march=native), which the
# page's WebAssembly never does. On the default x86-64 target there is none to fuse: the same code.
add_compile_options($<$<COMPILE_LANGUAGE:CXX>:-ffp-contract=off>)
