# Builds TARGETS (each includes one header its library must not see) and passes only when
# the build fails and the compiler reports every one of HEADERS as not found.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGETS} -- -k
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "forbidden includes compiled: ${TARGETS}")
endif()
foreach(header ${HEADERS})
  string(FIND "${output}" "${header}: No such file or directory" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${header} was not refused as not found:\n${output}")
  endif()
endforeach()
list(LENGTH HEADERS count)
message(STATUS "${count} forbidden headers refused")
