# Copies the page into OUT: its own files (SRC), the WebAssembly module (WASM), uPlot from the
# npm install (NPM) and the QR code generator from Debian (QRCODE: node-qrcode-generator's
# qrcode.js); everything the page loads is local, nothing is fetched at run time.
file(MAKE_DIRECTORY ${OUT})
file(GLOB files ${SRC}/*)
foreach(f ${files} ${WASM} ${NPM}/uplot/dist/uPlot.iife.min.js ${NPM}/uplot/dist/uPlot.min.css
        ${NPM}/uplot/LICENSE ${QRCODE})
  get_filename_component(name ${f} NAME)
  if(name STREQUAL "LICENSE")
    set(name uPlot.LICENSE.txt)
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${f} ${OUT}/${name}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cannot copy ${f} to ${OUT}")
  endif()
endforeach()
