
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/apps/cli_common.cpp" "CMakeFiles/whatnext.dir/apps/cli_common.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/cli_common.cpp.o.d"
  "/work/main/apps/cmd_animate.cpp" "CMakeFiles/whatnext.dir/apps/cmd_animate.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/cmd_animate.cpp.o.d"
  "/work/main/apps/cmd_optimize.cpp" "CMakeFiles/whatnext.dir/apps/cmd_optimize.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/cmd_optimize.cpp.o.d"
  "/work/main/apps/cmd_plot.cpp" "CMakeFiles/whatnext.dir/apps/cmd_plot.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/cmd_plot.cpp.o.d"
  "/work/main/apps/cmd_run.cpp" "CMakeFiles/whatnext.dir/apps/cmd_run.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/cmd_run.cpp.o.d"
  "/work/main/apps/cmd_sweep.cpp" "CMakeFiles/whatnext.dir/apps/cmd_sweep.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/cmd_sweep.cpp.o.d"
  "/work/main/apps/whatnext.cpp" "CMakeFiles/whatnext.dir/apps/whatnext.cpp.o" "gcc" "CMakeFiles/whatnext.dir/apps/whatnext.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build/CMakeFiles/whatnext_io.dir/DependInfo.cmake"
  "/work/main/build/CMakeFiles/whatnext_core.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
