file(REMOVE_RECURSE
  "CMakeFiles/whatnext.dir/apps/cli_common.cpp.o"
  "CMakeFiles/whatnext.dir/apps/cli_common.cpp.o.d"
  "CMakeFiles/whatnext.dir/apps/cmd_animate.cpp.o"
  "CMakeFiles/whatnext.dir/apps/cmd_animate.cpp.o.d"
  "CMakeFiles/whatnext.dir/apps/cmd_optimize.cpp.o"
  "CMakeFiles/whatnext.dir/apps/cmd_optimize.cpp.o.d"
  "CMakeFiles/whatnext.dir/apps/cmd_plot.cpp.o"
  "CMakeFiles/whatnext.dir/apps/cmd_plot.cpp.o.d"
  "CMakeFiles/whatnext.dir/apps/cmd_run.cpp.o"
  "CMakeFiles/whatnext.dir/apps/cmd_run.cpp.o.d"
  "CMakeFiles/whatnext.dir/apps/cmd_sweep.cpp.o"
  "CMakeFiles/whatnext.dir/apps/cmd_sweep.cpp.o.d"
  "CMakeFiles/whatnext.dir/apps/whatnext.cpp.o"
  "CMakeFiles/whatnext.dir/apps/whatnext.cpp.o.d"
  "whatnext"
  "whatnext.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/whatnext.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
