# SPDX-License-Identifier: LGPL-2.1-or-later
# Install rules and the Debian package for the workbench.
#
# Everything a user needs lands in one install component, `workbench`, laid out the way Debian's
# FreeCAD scans its Mod folders: <prefix>/share/freecad/Mod/VarSurf/ holding Init.py, InitGui.py,
# package.xml, Resources/ and src/varsurf/ (Python sources plus the _native extension). Init.py
# finds the package at <Mod folder>/src/varsurf, as in a checkout. Nothing else in the project has
# install rules; the component list below keeps it that way for the package.
#
# Build the package on demand from the build directory: `cpack -G DEB` (or the `package` target);
# it is not part of the default build.

include(GNUInstallDirs)
if(NOT VARSURF_MOD_DESTINATION)
  set(VARSURF_MOD_DESTINATION ${CMAKE_INSTALL_DATADIR}/freecad/Mod/VarSurf)
endif()

install(FILES Init.py InitGui.py package.xml
  DESTINATION ${VARSURF_MOD_DESTINATION}
  COMPONENT workbench)
install(DIRECTORY Resources/
  DESTINATION ${VARSURF_MOD_DESTINATION}/Resources
  COMPONENT workbench)
# The Python package tree, sources only: the in-place extension is not copied (the _native target
# installs its own build, see src/binding), and neither are caches or tests.
install(DIRECTORY src/varsurf/
  DESTINATION ${VARSURF_MOD_DESTINATION}/src/varsurf
  COMPONENT workbench
  FILES_MATCHING PATTERN "*.py"
  PATTERN "__pycache__" EXCLUDE
  PATTERN "tests" EXCLUDE)
# The module the commands are registered from (its name is what recorded macros import).
install(FILES src/VarSurfGui.py
  DESTINATION ${VARSURF_MOD_DESTINATION}/src
  COMPONENT workbench)
# Debian's place for the licence (machine-readable copyright, pointing to the LGPL's full text).
install(FILES cmake/copyright
  DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/varsurf
  COMPONENT workbench)

# Package metadata comes from package.xml, the file FreeCAD's Addon Manager reads too.
file(READ ${PROJECT_SOURCE_DIR}/package.xml _varsurf_package_xml)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/package.xml)
string(REGEX MATCH "<description>([^<]*)</description>" _ "${_varsurf_package_xml}")
string(STRIP "${CMAKE_MATCH_1}" VARSURF_DESCRIPTION)
string(REGEX MATCH "<maintainer email=\"([^\"]*)\">([^<]*)</maintainer>" _ "${_varsurf_package_xml}")
set(VARSURF_MAINTAINER_NAME "${CMAKE_MATCH_2}")
set(VARSURF_MAINTAINER "${CMAKE_MATCH_2} <${CMAKE_MATCH_1}>")
string(REGEX MATCH "<version>([^<]*)</version>" _ "${_varsurf_package_xml}")
if(NOT CMAKE_MATCH_1 STREQUAL PROJECT_VERSION)
  message(WARNING "package.xml has version ${CMAKE_MATCH_1}, project() has ${PROJECT_VERSION}: "
    "the Debian package takes project()'s")
endif()
if(VARSURF_DESCRIPTION STREQUAL "" OR VARSURF_MAINTAINER_NAME STREQUAL "")
  message(FATAL_ERROR "package.xml lacks a description or a maintainer with an email")
endif()

set(CPACK_PACKAGE_NAME varsurf)
set(CPACK_PACKAGE_VENDOR "${VARSURF_MAINTAINER_NAME}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "FreeCAD workbench for variational B-spline surfaces")
set(CPACK_PACKAGE_DESCRIPTION "${VARSURF_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES ON)

# Only the workbench component, as one package named varsurf.
set(CPACK_COMPONENTS_ALL workbench)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)

set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_PACKAGE_NAME varsurf)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${VARSURF_MAINTAINER}")
# Synopsis line: CPACK_PACKAGE_DESCRIPTION_SUMMARY; extended description: package.xml's.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "${VARSURF_DESCRIPTION}")
# dpkg-shlibdeps (dpkg-dev) adds the libraries _native links: OCCT, SuiteSparse, the C++ runtime.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The extension is built for FreeCAD's interpreter (CPython 3.11 ABI); numpy is imported by the
# sheet model; matplotlib only draws the optional analysis plots.
math(EXPR _varsurf_next_minor "${Python3_VERSION_MINOR} + 1")
set(CPACK_DEBIAN_PACKAGE_DEPENDS
  "freecad (>= 0.20), python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}~), python3 (<< ${Python3_VERSION_MAJOR}.${_varsurf_next_minor}), python3-numpy")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS python3-matplotlib)

include(CPack)
