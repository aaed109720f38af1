# The unit tests laid out like the code: test/unit/<module>/test_*.cpp, one test binary per folder
# (test_<folder>), found by glob in the catkin build (CMakeLists.txt) and in the ROS-free one
# (cmake/ros_free.cmake) alike; support/ holds the shared fixtures and main. A test added to a
# folder joins its binary with no list to keep.

# The folders of test/unit/ that hold tests (all but support/).
function(pe_unit_test_folders out)
  file(GLOB folders LIST_DIRECTORIES true RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}/test/unit"
    "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/*")
  set(result)
  foreach(folder ${folders})
    if(IS_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/${folder}" AND NOT folder STREQUAL "support")
      list(APPEND result ${folder})
    endif()
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# A folder's test sources. test_no_allocation.cpp replaces the global operator new to count
# allocations, so it is a binary of its own (test_no_allocation), not part of its folder's.
function(pe_unit_test_sources folder out)
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/${folder}/test_*.cpp")
  list(FILTER sources EXCLUDE REGEX "/test_no_allocation\\.cpp$")
  set(${out} ${sources} PARENT_SCOPE)
endfunction()
