# `cmake --install build --prefix P` installs the SDK: headers under P/include/slambox/,
# the static libraries slambox::core, slambox::sim, slambox::eval, and the CMake package
# (find_package(slambox CONFIG REQUIRED)); also the slambox executable and the shipped
# MRPT plugin with its manifest. docs/plugins.md describes the API.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(slambox_sdk_libraries slambox_core slambox_sim slambox_eval)
set_target_properties(slambox_core PROPERTIES EXPORT_NAME core)
set_target_properties(slambox_sim PROPERTIES EXPORT_NAME sim)
set_target_properties(slambox_eval PROPERTIES EXPORT_NAME eval)
add_library(slambox::core ALIAS slambox_core)
add_library(slambox::sim ALIAS slambox_sim)
add_library(slambox::eval ALIAS slambox_eval)

install(TARGETS ${slambox_sdk_libraries} EXPORT slamboxTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(dir core sim eval)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/slambox/${dir}
          FILES_MATCHING PATTERN "*.hpp")
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/generated/core/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/slambox/core)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/slambox)
install(EXPORT slamboxTargets NAMESPACE slambox:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/slamboxConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/slamboxConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/slamboxConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/slamboxConfig.cmake ${PROJECT_BINARY_DIR}/slamboxConfigVersion.cmake
        DESTINATION ${config_dir})

install(TARGETS slambox RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS slambox_render_library LIBRARY DESTINATION lib/slambox)
install(TARGETS slambox_mrpt_plugin LIBRARY DESTINATION lib/slambox/plugins)
install(FILES ${SLAMBOX_PLUGIN_BUILD_DIR}/slambox-mrpt.manifest.json DESTINATION lib/slambox/plugins)
