# Install rules and the exported CMake package MC1 (docs/library.md).
#
# mc1_install(TARGET [EXPORT_NAME NAME] [HEADERS file...] [PIC])
#   next to a library: installs it into the MC1Targets export set (as
#   MC1::NAME, default the target's name) and the HEADERS (relative to the
#   calling folder, or absolute for generated ones) into include/mc1/. The
#   tree's headers include each other by bare name, so include/mc1 is the
#   installed targets' include directory; the build's own include directories
#   (source and build tree) are kept for the build only. PIC: compiled
#   position-independent, for the Python module (python/) to link; with
#   -fno-semantic-interposition so that calls inside the library stay as
#   fast as without.
# mc1_install_package() once, at the end of the top-level CMakeLists.txt:
#   MC1Config.cmake, its version file, MC1Targets.cmake, mc1.pc and
#   mc1-platform.pc.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MC1_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/MC1)
set(MC1_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/mc1)
set(MC1_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/mc1)

function(mc1_install target)
  cmake_parse_arguments(arg "PIC" "EXPORT_NAME" "HEADERS" ${ARGN})
  foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs ${target} ${prop})
    if(NOT dirs)
      continue()
    endif()
    set(kept)
    foreach(d IN LISTS dirs)
      if(d MATCHES "^(${PROJECT_SOURCE_DIR}|${PROJECT_BINARY_DIR})(/|$)")
        list(APPEND kept "$<BUILD_INTERFACE:${d}>")
      else()
        list(APPEND kept "${d}")
      endif()
    endforeach()
    set_target_properties(${target} PROPERTIES ${prop} "${kept}")
  endforeach()
  if(arg_EXPORT_NAME)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${arg_EXPORT_NAME})
  endif()
  get_target_property(type ${target} TYPE)
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE
      $<INSTALL_INTERFACE:${MC1_INSTALL_INCLUDEDIR}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    # libmc1_*.a in the prefix's lib/, not a bare libapu_core.a.
    if(NOT target MATCHES "^mc1_")
      set_target_properties(${target} PROPERTIES OUTPUT_NAME mc1_${target})
    endif()
    # The .pc files list the archives dependents first: targets are defined
    # after the libraries they use, so that is the reverse of this order.
    # mc1-platform.pc has those on SystemC (and requires it), mc1.pc the
    # others: a program on mc1.pc alone needs no sc_main.
    get_target_property(out ${target} OUTPUT_NAME)
    if(NOT out)
      set(out ${target})
    endif()
    get_target_property(links ${target} LINK_LIBRARIES)
    get_property(on_systemc GLOBAL PROPERTY MC1_SYSTEMC_TARGETS)
    set(pc MC1_ARCHIVES)
    foreach(l IN LISTS links)
      if(l STREQUAL "PkgConfig::SYSTEMC" OR l IN_LIST on_systemc)
        set(pc MC1_PLATFORM_ARCHIVES)
        set_property(GLOBAL APPEND PROPERTY MC1_SYSTEMC_TARGETS ${target})
        break()
      endif()
    endforeach()
    set_property(GLOBAL APPEND PROPERTY ${pc} ${out})
  endif()
  if(arg_PIC)
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  endif()
  install(TARGETS ${target} EXPORT MC1Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  if(arg_HEADERS)
    list(TRANSFORM arg_HEADERS PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/ REGEX "^[^/]")
    install(FILES ${arg_HEADERS} DESTINATION ${MC1_INSTALL_INCLUDEDIR})
  endif()
endfunction()

function(mc1_install_package)
  install(EXPORT MC1Targets NAMESPACE MC1:: DESTINATION ${MC1_INSTALL_CMAKEDIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/MC1Config.cmake.in
    ${PROJECT_BINARY_DIR}/MC1Config.cmake INSTALL_DESTINATION ${MC1_INSTALL_CMAKEDIR}
    PATH_VARS MC1_INSTALL_DATADIR)
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/MC1ConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/MC1Config.cmake ${PROJECT_BINARY_DIR}/MC1ConfigVersion.cmake
    DESTINATION ${MC1_INSTALL_CMAKEDIR})
  # The .pc files find the prefix from their own place (an install with --prefix).
  string(REGEX REPLACE "[^/]+" ".." MC1_PC_PREFIX ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
  foreach(pc mc1 mc1-platform)
    string(TOUPPER ${pc} var)
    string(REPLACE "-" "_" var ${var})
    get_property(archives GLOBAL PROPERTY ${var}_ARCHIVES)
    list(REVERSE archives)
    list(TRANSFORM archives PREPEND -l)
    list(JOIN archives " " MC1_PC_LIBS)
    configure_file(${PROJECT_SOURCE_DIR}/cmake/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
    install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
  endforeach()
endfunction()
