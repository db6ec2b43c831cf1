# Debian packages through CPack: `cpack -G DEB` in a build tree (with the tools built) writes
#   libraps0      the shared library (and its soname link)
#   libraps-dev   the header, libraps.so, the CMake package files and raps.pc
#   raps-tools    raps-param and raps-gltf, with manual pages made from their --help
# The install() rules name these components (src/, samples/); tests/packaging/deb.cmake unpacks
# the packages into a scratch root and builds and runs against them.
set(CPACK_PACKAGE_NAME raps)
set(CPACK_PACKAGE_VENDOR "raps")
set(CPACK_PACKAGE_CONTACT "raps maintainers <raps@localhost>")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
# Each description's first line is the package's synopsis (CPack adds the indentation).
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL libraps0 libraps-dev)
set(CPACK_DEBIAN_PACKAGE_SECTION libs)
# dpkg-shlibdeps writes each package's dependencies on the C and C++ runtimes; the packages'
# dependencies on each other come from the component dependencies below.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The tools' libraps.so.0 is in this build tree, not in an installed package: dpkg-shlibdeps
# finds it here (it has no dependency information: --ignore-missing-info, which CPack passes).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR}/src)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)
set(CPACK_DEBIAN_LIBRAPS0_PACKAGE_NAME libraps0)
set(CPACK_DEBIAN_LIBRAPS0_DESCRIPTION "r-adaptive surface parameterization: shared library
raps computes texture coordinates for triangle meshes (disk, atlas and sphere domains)
behind a small, stable C ABI.")
set(CPACK_DEBIAN_LIBRAPS-DEV_PACKAGE_NAME libraps-dev)
set(CPACK_DEBIAN_LIBRAPS-DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_LIBRAPS-DEV_DESCRIPTION "r-adaptive surface parameterization: development files
The C header raps.h, libraps.so, the CMake package (find_package(raps), target raps::raps)
and the pkg-config file raps.pc.")
if(TARGET raps-param)
  list(APPEND CPACK_COMPONENTS_ALL raps-tools)
  set(CPACK_DEBIAN_RAPS-TOOLS_PACKAGE_NAME raps-tools)
  set(CPACK_DEBIAN_RAPS-TOOLS_PACKAGE_SECTION graphics)
  set(CPACK_DEBIAN_RAPS-TOOLS_DESCRIPTION "r-adaptive surface parameterization: command-line tools
raps-param maps OBJ/OFF meshes (disk, atlas, sphere) and writes OBJ with texture coordinates;
raps-gltf bakes atlas texture coordinates into glTF 2.0 assets.")
endif()
include(CPack)
cpack_add_component(libraps0)
cpack_add_component(libraps-dev DEPENDS libraps0)
if(TARGET raps-param)
  cpack_add_component(raps-tools DEPENDS libraps0)
endif()
