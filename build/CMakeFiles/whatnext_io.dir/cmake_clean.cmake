file(REMOVE_RECURSE
  "CMakeFiles/whatnext_io.dir/generated/examples_embedded.cpp.o"
  "CMakeFiles/whatnext_io.dir/generated/examples_embedded.cpp.o.d"
  "CMakeFiles/whatnext_io.dir/src/config.cpp.o"
  "CMakeFiles/whatnext_io.dir/src/config.cpp.o.d"
  "CMakeFiles/whatnext_io.dir/src/output.cpp.o"
  "CMakeFiles/whatnext_io.dir/src/output.cpp.o.d"
  "generated/examples_embedded.cpp"
  "libwhatnext_io.a"
  "libwhatnext_io.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/whatnext_io.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
