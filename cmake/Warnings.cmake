# Applied per target so that third-party headers (included as SYSTEM) stay quiet.
function(subfeed_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                                           -Wnon-virtual-dtor -Wold-style-cast)
  # GCC 12 reports false -Wrestrict overlaps in std::string's operator+ at -O2 (GCC bug
  # 105651, fixed in 13); it fires on ordinary message building.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(SUBFEED_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(SUBFEED_SANITIZE)
  # -O1: AddressSanitizer's reports stay exact (frame pointers kept), and Eigen's templates
  # run several times faster than at -O0, so whole plans fit in the sanitizer's test run.
  # Instrumented code at -O1 makes GCC 12 report maybe-uninitialized inside libstdc++'s
  # <regex>; the release build keeps that warning.
  add_compile_options(-O1 -fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined -Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
  # Eigen's small functions are only `inline` to GCC. The instrumented geometry leaves many
  # uninlined, and the linker then takes the first copy it meets: the -O0 one of a test
  # file. Forced inline, Eigen's arithmetic runs at the geometry's -O2 wherever it is called.
  add_compile_definitions("EIGEN_STRONG_INLINE=__attribute__((always_inline)) inline")
endif()
