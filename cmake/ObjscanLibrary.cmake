# The installable library: one shared library objscan::objscan (libobjscan.so) made of every module's
# objects, its headers, the config/ folder (share/objscan/config) and a CMake package, so that
#   find_package(objscan REQUIRED)  target_link_libraries(app PRIVATE objscan::objscan)
# works against an installed tree. Shared, so that Embree, PCL, OctoMap, Assimp, yaml-cpp, libpng and
# tinyxml2 stay private: a consumer needs only Eigen (the headers use it) and the runtime libraries.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

get_property(objscan_modules GLOBAL PROPERTY OBJSCAN_MODULE_LIBRARIES)
get_property(objscan_private_deps GLOBAL PROPERTY OBJSCAN_MODULE_PRIVATE_DEPS)
set(objscan_objects)
foreach(module ${objscan_modules})
  list(APPEND objscan_objects $<TARGET_OBJECTS:${module}>)
endforeach()
add_library(objscan_library SHARED ${objscan_objects})
add_library(objscan::objscan ALIAS objscan_library)
set_target_properties(objscan_library PROPERTIES
  OUTPUT_NAME objscan EXPORT_NAME objscan
  VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
  LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib)
target_include_directories(objscan_library PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(objscan_library PUBLIC cxx_std_17)
target_link_libraries(objscan_library PUBLIC Eigen3::Eigen Threads::Threads PRIVATE ${objscan_private_deps} ${CMAKE_DL_LIBS})
# A library with an undefined symbol fails here, not in the consumer's link. Not with sanitizers:
# clang links their runtimes into programs only, a shared library takes __asan_*/__ubsan_* from the
# program that loads it, so they are undefined in libobjscan.so by design.
if(NOT OBJSCAN_SANITIZE)
  target_link_options(objscan_library PRIVATE -Wl,--no-undefined)
endif()

# Headers of the library; the tests' helpers (gtest) stay out.
file(GLOB_RECURSE objscan_public_headers RELATIVE ${PROJECT_SOURCE_DIR}/src CONFIGURE_DEPENDS
     ${PROJECT_SOURCE_DIR}/src/objscan/*.h)
foreach(header ${objscan_public_headers})
  if(header MATCHES "/testing/|/test_[^/]*\\.h$|/shape_database_suite\\.h$")
    continue()
  endif()
  get_filename_component(folder ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/src/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${folder} COMPONENT library)
endforeach()

install(TARGETS objscan_library EXPORT objscanTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT library
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS objscan RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT app)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${OBJSCAN_INSTALL_CONFIGDIR} COMPONENT library)
install(EXPORT objscanTargets NAMESPACE objscan:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/objscan COMPONENT library)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/objscanConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/objscanConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/objscan
                              PATH_VARS OBJSCAN_INSTALL_CONFIGDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/objscanConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/objscanConfig.cmake ${PROJECT_BINARY_DIR}/objscanConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/objscan COMPONENT library)
