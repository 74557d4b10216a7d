# The native binaries compute with musl's maths (cmake/maths.cmake), not the C library's: none of
# them imports one of musl's functions from a shared library. A link that put the system's libm
# first would pass every other test on this machine and differ from the page on another.
#   cmake -DNM=... "-DFUNCTIONS=sin;cos;..." "-DFILES=a;b;..." -P maths_imports.cmake
foreach(file ${FILES})
  execute_process(COMMAND ${NM} -D --undefined-only ${file} OUTPUT_VARIABLE imports RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "${NM} could not read ${file}")
  endif()
  foreach(name ${FUNCTIONS})
    if(imports MATCHES "[ \n]${name}(@|\n)")
      message(FATAL_ERROR "${file} takes ${name} from the C library, not from musl (cmake/maths.cmake)")
    endif()
  endforeach()
  message(STATUS "${file}: none of ${FUNCTIONS} from a shared library")
endforeach()
