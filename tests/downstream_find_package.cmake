# Installs contact-ode from BUILD_DIR into WORK/prefix, then configures, builds and runs the
# downstream project in SOURCE against that prefix, twice: with the default flags and with
# -march=native, so that one of the two is built with other SIMD flags than the library (whichever
# it was built with), as a user's program may be. Any failing step fails the test.
foreach(var BUILD_DIR SOURCE WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "downstream_find_package.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed (${code}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix)
foreach(name default native)
  set(build ${WORK}/build-${name})
  set(flags "")
  if(name STREQUAL "native")
    set(flags -march=native)
  endif()
  step(${CMAKE_COMMAND} -S ${SOURCE} -B ${build} -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=Release
       -DCMAKE_CXX_FLAGS=${flags})
  step(${CMAKE_COMMAND} --build ${build})
  step(${build}/downstream)
endforeach()
