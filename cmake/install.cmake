# cmake --install BUILD --prefix P: the public headers under P/include/deb/,
# the layer libraries, the CLI, and the CMake package deb under
# P/lib/cmake/deb, so that an application does
#   find_package(deb CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE deb::deb)
include(CMakePackageConfigHelpers)

# Public headers: every header under deb/ whose first line is not the
# internal marker; deb/deb.h must include each of them.
set(deb_internal_marker "// Internal: not part of the public API.")
file(READ ${PROJECT_SOURCE_DIR}/deb/deb.h deb_umbrella)
file(GLOB_RECURSE deb_headers RELATIVE ${PROJECT_SOURCE_DIR} CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/deb/*.h)
foreach(header IN LISTS deb_headers)
  file(STRINGS ${PROJECT_SOURCE_DIR}/${header} first_line LIMIT_COUNT 1)
  if(first_line STREQUAL deb_internal_marker)
    continue()
  endif()
  string(FIND "${deb_umbrella}" "#include \"${header}\"" at)
  if(NOT header STREQUAL "deb/deb.h" AND at EQUAL -1)
    message(FATAL_ERROR "${header} is public (its first line is not \"${deb_internal_marker}\") "
                        "but deb/deb.h does not include it")
  endif()
  get_filename_component(dir ${header} DIRECTORY)
  install(FILES ${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${dir})
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/generated/deb/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/deb)

set(deb_config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/deb)
install(TARGETS deb_core deb_units deb_parameters deb_spectra deb_signal deb_systems deb_models deb_budget deb_uncertainty deb_optimise deb_formats deb_load deb_results deb_report_figure
                deb_report_document deb_report_budget deb_report_measurement deb_report_compare deb_report
                deb_lib
        EXPORT debTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS deb RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT debTargets NAMESPACE deb:: DESTINATION ${deb_config_dir})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/debConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/cmake/debConfig.cmake
                              INSTALL_DESTINATION ${deb_config_dir} NO_SET_AND_CHECK_MACRO
                              NO_CHECK_REQUIRED_COMPONENTS_MACRO)
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/debConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/debConfig.cmake ${PROJECT_BINARY_DIR}/cmake/debConfigVersion.cmake
        DESTINATION ${deb_config_dir})
