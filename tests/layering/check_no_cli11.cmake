# Passes when no source of a library (everything but src/cli, the simulator's front and the
# tests) includes CLI11.
file(GLOB_RECURSE sources
     ${ROOT}/base/*.?pp ${ROOT}/gcode/*.?pp ${ROOT}/src/cl/*.?pp ${ROOT}/src/geometry/*.?pp
     ${ROOT}/src/job/*.?pp ${ROOT}/postprocessors/*.?pp ${ROOT}/drivers/*.?pp ${ROOT}/sim/*.?pp)
foreach(source ${sources})
  if(source MATCHES "/sim/sim_main\\.cpp$")
    continue() # the simulator's own command line
  endif()
  file(STRINGS ${source} lines REGEX "#include [<\"]CLI/")
  if(lines)
    message(FATAL_ERROR "${source} includes CLI11: ${lines}")
  endif()
endforeach()
list(LENGTH sources count)
message(STATUS "${count} library sources, none includes CLI11")
