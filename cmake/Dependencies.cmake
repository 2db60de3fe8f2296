# Debian 12 packages only (scripts/bootstrap installs them).
find_package(PkgConfig REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Boost 1.74 REQUIRED) # header-only Asio
find_package(Threads REQUIRED)
pkg_check_modules(SERIALPORT REQUIRED IMPORTED_TARGET libserialport)
pkg_check_modules(TOMLPP REQUIRED IMPORTED_TARGET tomlplusplus)

# Debian's OpenSubdiv package config references libosdCPU.a, which the package does not
# ship, so find the shared library and headers directly.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/bfr/surfaceFactory.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY NAMES osdCPU REQUIRED)
add_library(subfeed_opensubdiv INTERFACE)
target_include_directories(subfeed_opensubdiv SYSTEM INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
target_link_libraries(subfeed_opensubdiv INTERFACE ${OPENSUBDIV_CPU_LIBRARY})
add_library(OpenSubdiv::cpu ALIAS subfeed_opensubdiv)
