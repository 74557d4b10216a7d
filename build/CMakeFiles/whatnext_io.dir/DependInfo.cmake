
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/build/generated/examples_embedded.cpp" "CMakeFiles/whatnext_io.dir/generated/examples_embedded.cpp.o" "gcc" "CMakeFiles/whatnext_io.dir/generated/examples_embedded.cpp.o.d"
  "/work/main/src/config.cpp" "CMakeFiles/whatnext_io.dir/src/config.cpp.o" "gcc" "CMakeFiles/whatnext_io.dir/src/config.cpp.o.d"
  "/work/main/src/output.cpp" "CMakeFiles/whatnext_io.dir/src/output.cpp.o" "gcc" "CMakeFiles/whatnext_io.dir/src/output.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build/CMakeFiles/whatnext_core.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
