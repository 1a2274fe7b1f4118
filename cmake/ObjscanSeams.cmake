# The seams the build keeps: the method's libraries (mapping, segmentation, recognition, planning,
# scanning) reach a robot only through platform::Platform, so they must not link the simulator.
#
# Three checks: objscan_forbid_links stops the configuration when a target links a forbidden one,
# directly or through any chain of libraries (PUBLIC, PRIVATE or INTERFACE); objscan_forbid_includes
# stops it when a library source of a folder includes a header of a forbidden folder (header-only
# code links nothing); and the program tests/without_sim/ links every object of those libraries
# (whole archives) without the simulator, so a symbol of sim/ used anywhere in them fails the build.
# The method's tests may render and place views with the simulator (TEST_DEPS objscan_sim).

# Every target `target` links, directly or not, into `out_var`.
function(objscan_link_closure target out_var)
  set(seen "")
  set(pending ${target})
  while(pending)
    list(POP_FRONT pending current)
    if(NOT TARGET ${current} OR current IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${current})
    get_target_property(type ${current} TYPE)
    set(links "")
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(direct ${current} LINK_LIBRARIES)
      if(direct)
        list(APPEND links ${direct})
      endif()
    endif()
    get_target_property(interface ${current} INTERFACE_LINK_LIBRARIES)
    if(interface)
      list(APPEND links ${interface})
    endif()
    foreach(item ${links})
      # Private dependencies of static libraries appear as $<LINK_ONLY:name>.
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
      if(TARGET ${item})
        list(APPEND pending ${item})
      endif()
    endforeach()
  endwhile()
  list(REMOVE_ITEM seen ${target})
  set(${out_var} ${seen} PARENT_SCOPE)
endfunction()

function(objscan_forbid_links)
  cmake_parse_arguments(F "" "" "TARGETS;FORBIDDEN" ${ARGN})
  foreach(target ${F_TARGETS})
    objscan_link_closure(${target} closure)
    foreach(forbidden ${F_FORBIDDEN})
      if(forbidden IN_LIST closure)
        message(FATAL_ERROR "${target} links ${forbidden} (directly or through other libraries): the method reaches "
                            "a robot only through platform::Platform (cmake/ObjscanSeams.cmake, docs/architecture.md)")
      endif()
    endforeach()
  endforeach()
endfunction()

# Library sources (not *_test.cc, testing/ or test_*.h helpers) of each of FOLDERS (below src/objscan)
# must not include a header of any of FORBIDDEN.
function(objscan_forbid_includes)
  cmake_parse_arguments(F "" "" "FOLDERS;FORBIDDEN" ${ARGN})
  foreach(folder ${F_FOLDERS})
    file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/objscan/${folder}/*.h
         ${PROJECT_SOURCE_DIR}/src/objscan/${folder}/*.cc)
    foreach(source ${sources})
      if(source MATCHES "_test\\.cc$|/testing/|/test_[^/]*\\.h$")
        continue()
      endif()
      foreach(forbidden ${F_FORBIDDEN})
        file(STRINGS ${source} hits REGEX "#include \"objscan/${forbidden}/")
        if(hits)
          file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${source})
          message(FATAL_ERROR "${relative} includes objscan/${forbidden}/: the method reaches a robot only through "
                              "platform::Platform (cmake/ObjscanSeams.cmake, docs/architecture.md)")
        endif()
      endforeach()
    endforeach()
  endforeach()
endfunction()

set(OBJSCAN_METHOD_LIBRARIES objscan_mapping objscan_segmentation objscan_recognition objscan_planning objscan_scanning)
objscan_forbid_links(TARGETS ${OBJSCAN_METHOD_LIBRARIES} FORBIDDEN objscan_sim)
objscan_forbid_includes(FOLDERS mapping segmentation recognition planning scanning FORBIDDEN sim)

# ROS stays in ros/'s glue (ros_messages.*, the two nodes): no file of src/objscan nor of the ROS-free
# bridge (ros/bridge/, which a ROS 2 bridge reuses) includes a ROS 1 header.
function(objscan_forbid_ros_includes)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/objscan/*.h ${PROJECT_SOURCE_DIR}/src/objscan/*.cc
       ${PROJECT_SOURCE_DIR}/ros/bridge/*.h ${PROJECT_SOURCE_DIR}/ros/bridge/*.cc)
  foreach(source ${sources})
    file(STRINGS ${source} hits REGEX
         "#include [<\"](ros|tf|tf2|tf2_ros|std_msgs|geometry_msgs|sensor_msgs|nav_msgs|visualization_msgs|rosbag)/")
    if(hits)
      file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${source})
      message(FATAL_ERROR "${relative} includes a ROS header: ROS headers belong in ros/'s glue only "
                          "(cmake/ObjscanSeams.cmake, docs/ros.md)")
    endif()
  endforeach()
endfunction()
objscan_forbid_ros_includes()
