# Installs the library as a CMake package (find_package(Penumbra CONFIG)) and a pkg-config
# file. The libraries are static, so the package also carries glad and names every system
# dependency; PenumbraConfig.cmake finds them again in the consumer's build.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PENUMBRA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Penumbra)
set_target_properties(glad PROPERTIES EXPORT_NAME glad)
install(TARGETS penumbra penumbra_core penumbra_gpu penumbra_app glad
        EXPORT PenumbraTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/renderer/include/penumbra
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT PenumbraTargets NAMESPACE penumbra:: DESTINATION ${PENUMBRA_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/PenumbraConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/PenumbraConfig.cmake INSTALL_DESTINATION ${PENUMBRA_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/PenumbraConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/PenumbraConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/PenumbraConfigVersion.cmake
        DESTINATION ${PENUMBRA_CMAKE_DIR})
file(RELATIVE_PATH PENUMBRA_PC_TO_PREFIX "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
configure_file(${PROJECT_SOURCE_DIR}/cmake/penumbra.pc.in
               ${CMAKE_CURRENT_BINARY_DIR}/penumbra.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/penumbra.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
