# musl's maths in the native build gives the same bits as Emscripten's in the page: tests/maths_probe.cpp
# built both ways, on the same arguments, prints the same hash of every function's results.
#   cmake -DNODE=... -DWASM=maths_probe.js -DNATIVE=maths_probe -P maths_wasm.cmake
foreach(seed 1 20261129)
  execute_process(COMMAND ${NATIVE} ${seed} 5000 OUTPUT_VARIABLE native RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "${NATIVE} failed")
  endif()
  execute_process(COMMAND ${NODE} ${WASM} ${seed} 5000 OUTPUT_VARIABLE wasm RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "${NODE} ${WASM} failed")
  endif()
  if(NOT native STREQUAL wasm)
    message(FATAL_ERROR "seed ${seed}: the native maths differ from the WebAssembly's\nnative:\n${native}WebAssembly:\n${wasm}")
  endif()
  message(STATUS "seed ${seed}: the same bits\n${native}")
endforeach()
