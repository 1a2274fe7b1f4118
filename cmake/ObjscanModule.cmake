# objscan_module(NAME name [DEPS target...] [PRIVATE_DEPS target...])
# Builds the static library objscan_<name> from every .cc below the module folder except *_test.cc,
# and, when tests are on, the test program objscan_<name>_test from the *_test.cc files (if any).
# Each module can be built and tested alone: `cmake --build build --target objscan_sim_test`.
# Modules are recorded (global properties OBJSCAN_MODULE_LIBRARIES, OBJSCAN_MODULE_PRIVATE_DEPS) for
# the installed shared library.
function(objscan_module)
  cmake_parse_arguments(M "" "NAME" "DEPS;PRIVATE_DEPS;TEST_DEPS" ${ARGN})
  file(GLOB_RECURSE all_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  set(lib_sources)
  set(test_sources)
  foreach(f ${all_sources})
    if(f MATCHES "_test\\.cc$")
      list(APPEND test_sources ${f})
    else()
      list(APPEND lib_sources ${f})
    endif()
  endforeach()
  set(lib objscan_${M_NAME})
  if(lib_sources)
    add_library(${lib} STATIC ${lib_sources})
    target_include_directories(${lib} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${lib} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS} objscan_warnings)
    # The modules' objects also make up the shared library objscan::objscan (cmake/ObjscanLibrary.cmake):
    # position independent, and without semantic interposition so calls inside objscan still inline
    # as in an executable.
    set_target_properties(${lib} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_compile_options(${lib} PRIVATE -fno-semantic-interposition)
    set_property(GLOBAL APPEND PROPERTY OBJSCAN_MODULE_LIBRARIES ${lib})
    set_property(GLOBAL APPEND PROPERTY OBJSCAN_MODULE_PRIVATE_DEPS ${M_PRIVATE_DEPS})
  else()
    add_library(${lib} INTERFACE)
    target_include_directories(${lib} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${lib} INTERFACE ${M_DEPS})
  endif()
  if(OBJSCAN_BUILD_TESTS AND test_sources)
    add_executable(${lib}_test ${test_sources})
    target_link_libraries(${lib}_test PRIVATE ${lib} ${M_TEST_DEPS} objscan_testing GTest::gtest GTest::gtest_main objscan_warnings)
    # Tests run from the project root so ../shared/data resolves as documented.
    gtest_discover_tests(${lib}_test WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} DISCOVERY_TIMEOUT 60
                         PROPERTIES LABELS ${M_NAME})
  endif()
endfunction()
