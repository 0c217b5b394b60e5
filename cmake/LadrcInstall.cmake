# SPDX-License-Identifier: BSD-3-Clause
# Installation and export of the library (with LADRC_INSTALL, ON when ladrc
# is the top-level project):
#   <prefix>/include/ladrc/*.h             public headers, version.h included
#   <prefix>/<libdir>/libladrc.a|.so        the library (BUILD_SHARED_LIBS picks)
#   <prefix>/<libdir>/cmake/ladrc/          ladrcConfig.cmake, ladrcConfigVersion.cmake
#                                           (SameMajorVersion), ladrcTargets*.cmake
#   <prefix>/<libdir>/pkgconfig/ladrc.pc    for pkg-config
#   <prefix>/share/doc/ladrc/               LICENSE, CHANGELOG.md, README.md
include_guard(GLOBAL)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LADRC_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/ladrc" CACHE STRING
    "Where ladrcConfig.cmake is installed, relative to the prefix")

install(TARGETS ladrc EXPORT ladrcTargets
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/ladrc"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
        FILES_MATCHING PATTERN "*.h")
install(FILES "${PROJECT_BINARY_DIR}/include/ladrc/version.h"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/ladrc")
# A LADRC_CONFIG header goes with the headers: the exported target and
# ladrc.pc name it, so users of the installed library compile as it was built.
if(LADRC_CONFIG_HEADER)
  install(FILES "${LADRC_CONFIG_HEADER}" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
endif()
install(EXPORT ladrcTargets NAMESPACE ladrc:: DESTINATION "${LADRC_INSTALL_CMAKEDIR}")

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/templates/ladrcConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/ladrcConfig.cmake"
  INSTALL_DESTINATION "${LADRC_INSTALL_CMAKEDIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/ladrcConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/ladrcConfig.cmake" "${PROJECT_BINARY_DIR}/ladrcConfigVersion.cmake"
        DESTINATION "${LADRC_INSTALL_CMAKEDIR}")

# pkg-config: the compile definitions the library was built with go to
# Cflags; libm goes to Libs for the static library (its users link it
# themselves), to Libs.private for the shared one.
set(LADRC_PC_CFLAGS "")
if(LADRC_REAL_DOUBLE)
  string(APPEND LADRC_PC_CFLAGS " -DLADRC_REAL_DOUBLE")
endif()
if(LADRC_STATUS_TEXTS STREQUAL "names")
  string(APPEND LADRC_PC_CFLAGS " -DLADRC_STATUS_NAMES_ONLY")
endif()
ladrc_select_variants(_ladrc_pc_sources _ladrc_pc_variants "" VARIANTS ${LADRC_VARIANTS} SHAPERS ${LADRC_SHAPERS}
                      HP_ONLINE ${LADRC_HP_ONLINE})
foreach(_ladrc_pc_def IN LISTS _ladrc_pc_variants)
  string(APPEND LADRC_PC_CFLAGS " -D${_ladrc_pc_def}")
endforeach()
if(LADRC_CONFIG_HEADER)
  get_filename_component(_ladrc_pc_config "${LADRC_CONFIG_HEADER}" NAME)
  string(APPEND LADRC_PC_CFLAGS " -DLADRC_CONFIG=${_ladrc_pc_config}")
endif()
set(LADRC_PC_LIBS "")
set(LADRC_PC_LIBS_PRIVATE "")
if(NOT WIN32)
  if(BUILD_SHARED_LIBS)
    set(LADRC_PC_LIBS_PRIVATE " -lm")
  else()
    set(LADRC_PC_LIBS " -lm")
  endif()
endif()
set(LADRC_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
    set(LADRC_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
  else()
    set(LADRC_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
  endif()
endforeach()
configure_file("${PROJECT_SOURCE_DIR}/cmake/templates/ladrc.pc.in" "${PROJECT_BINARY_DIR}/ladrc.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/ladrc.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")

install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" "${PROJECT_SOURCE_DIR}/CHANGELOG.md" "${PROJECT_SOURCE_DIR}/README.md"
        DESTINATION "${CMAKE_INSTALL_DOCDIR}")
