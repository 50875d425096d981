# `cmake --install build --prefix P` installs the drop-in subsystem: the two libraries (SPIR-V is embedded
# in them), their public headers, the engine's shared C++/GLSL headers, and a CMake package, so that a
# host writes
#   find_package(dyngi CONFIG REQUIRED)
#   target_link_libraries(my_host PRIVATE dyngi::gi)   # dyngi::engine comes with it
# The sample, the tools and the tests are not installed. examples/minimal_host builds against this
# package (scripts/test_install.sh).
include(CMakePackageConfigHelpers)
set(DYNGI_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/dyngi)

install(TARGETS dyngi_engine dyngi_gi EXPORT dyngiTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/ ${PROJECT_SOURCE_DIR}/gi_module/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/shaders/shared DESTINATION ${DYNGI_INSTALL_SHADER_INCLUDEDIR})
install(EXPORT dyngiTargets NAMESPACE dyngi:: DESTINATION ${DYNGI_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/dyngiConfig.cmake.in ${PROJECT_BINARY_DIR}/dyngiConfig.cmake
                              INSTALL_DESTINATION ${DYNGI_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/dyngiConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/dyngiConfig.cmake ${PROJECT_BINARY_DIR}/dyngiConfigVersion.cmake
        DESTINATION ${DYNGI_INSTALL_CMAKEDIR})
