
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/src/geometry.cpp" "CMakeFiles/whatnext_core.dir/src/geometry.cpp.o" "gcc" "CMakeFiles/whatnext_core.dir/src/geometry.cpp.o.d"
  "/work/main/src/model.cpp" "CMakeFiles/whatnext_core.dir/src/model.cpp.o" "gcc" "CMakeFiles/whatnext_core.dir/src/model.cpp.o.d"
  "/work/main/src/names.cpp" "CMakeFiles/whatnext_core.dir/src/names.cpp.o" "gcc" "CMakeFiles/whatnext_core.dir/src/names.cpp.o.d"
  "/work/main/src/simulate.cpp" "CMakeFiles/whatnext_core.dir/src/simulate.cpp.o" "gcc" "CMakeFiles/whatnext_core.dir/src/simulate.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
