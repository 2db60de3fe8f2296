# Builds TARGETS (each includes one header its library must not see) and passes only when
# the build fails and the compiler reports every one of HEADERS as not found.
# One build per target: a failing target stops the build, and keeping going takes a
# different flag under each generator.
set(output "")
foreach(target ${TARGETS})
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${target}
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(result EQUAL 0)
    message(FATAL_ERROR "a forbidden include compiled: ${target}")
  endif()
  string(APPEND output "${out}")
endforeach()
foreach(header ${HEADERS})
  string(FIND "${output}" "${header}: No such file or directory" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${header} was not refused as not found:\n${output}")
  endif()
endforeach()
list(LENGTH HEADERS count)
message(STATUS "${count} forbidden headers refused")
