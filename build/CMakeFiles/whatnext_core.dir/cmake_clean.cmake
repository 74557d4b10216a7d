file(REMOVE_RECURSE
  "CMakeFiles/whatnext_core.dir/src/geometry.cpp.o"
  "CMakeFiles/whatnext_core.dir/src/geometry.cpp.o.d"
  "CMakeFiles/whatnext_core.dir/src/model.cpp.o"
  "CMakeFiles/whatnext_core.dir/src/model.cpp.o.d"
  "CMakeFiles/whatnext_core.dir/src/names.cpp.o"
  "CMakeFiles/whatnext_core.dir/src/names.cpp.o.d"
  "CMakeFiles/whatnext_core.dir/src/simulate.cpp.o"
  "CMakeFiles/whatnext_core.dir/src/simulate.cpp.o.d"
  "libwhatnext_core.a"
  "libwhatnext_core.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/whatnext_core.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
