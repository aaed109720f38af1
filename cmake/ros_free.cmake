# The ROS-free build (PE_ROS_FREE=ON; make arm64 cross-builds it for the Raspberry Pi): the modules
# that compute, their unit tests and the core per-message benchmark, without catkin, so that it
# needs no ROS package for the target architecture. Included by CMakeLists.txt once the libraries
# the modules link are found.
include(cmake/pe_modules.cmake)

# The repository from its real path, for the tests' and the benchmark's data (test/data, config/).
get_filename_component(PE_REPO_DIR "${CMAKE_CURRENT_SOURCE_DIR}" REALPATH)

# Every unit test source but those that need what this build leaves out. Each test is judged by
# what its source includes or runs, so that a test added to any folder (or one that starts writing
# a bag) is judged the same way, with no list to keep:
#  - ROS: it includes a ROS header (ros/, rosbag/, a *_msgs package) or one of this package's ros/,
#    codecs/ or bag/ modules (the codecs, the parameters, the callback queue, the bag writer and reader):
#    roscpp, rosbag and the messages are not installable for arm64, and neither module is built here.
#  - The command-line tools: it includes a header of src/apps/ (the CLI layer) or names a tool's
#    path (PE_FIT_SURFACES, PE_SIMULATE, PE_ESTIMATOR_NODE, ... from src/apps/<tool>_main.cpp) to
#    run it or check its ldd: the tools link the CLI layer and with it rosbag, and are not built here.
#  - The fuzz corpora's replay (fuzz_inputs.h): its readers include the RCOut decoder and the bag.
file(GLOB_RECURSE PE_UNIT_TESTS CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/test_*.cpp")
file(GLOB PE_APPS_HEADERS CONFIGURE_DEPENDS RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}/src/apps"
  "${CMAKE_CURRENT_SOURCE_DIR}/src/apps/*.h")
file(GLOB PE_TOOL_MAINS CONFIGURE_DEPENDS RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}/src/apps"
  "${CMAKE_CURRENT_SOURCE_DIR}/src/apps/*_main.cpp")
string(REPLACE ";" "|" PE_APPS_HEADERS "${PE_APPS_HEADERS}")
string(REPLACE "_main.cpp" "" PE_TOOLS "${PE_TOOL_MAINS}")
string(REPLACE ";" "|" PE_TOOLS "${PE_TOOLS}")
string(TOUPPER "${PE_TOOLS}" PE_TOOLS)
string(REPLACE "." "\\." PE_APPS_HEADERS "${PE_APPS_HEADERS}")
set(PE_NEEDS_ROS_REGEX
  "^#include [<\"](ros|rosbag|[a-z_]+_msgs|propulsion_estimator/ros|propulsion_estimator/codecs|propulsion_estimator/bag)/"
  "^#include \"(${PE_APPS_HEADERS}|fuzz_inputs\\.h)\""
  "PE_(${PE_TOOLS})([^A-Z_]|$)")
string(REPLACE ";" "|" PE_NEEDS_ROS_REGEX "${PE_NEEDS_ROS_REGEX}")
set(PE_ROS_FREE_TESTS)
foreach(test_source ${PE_UNIT_TESTS})
  file(STRINGS "${test_source}" needs_ros REGEX "${PE_NEEDS_ROS_REGEX}")
  if(NOT needs_ros)
    list(APPEND PE_ROS_FREE_TESTS "${test_source}")
  endif()
endforeach()
# The choice reads the sources: configure again when one changes.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PE_UNIT_TESTS})
enable_testing()
find_package(GTest REQUIRED)
include(GoogleTest)
# One binary per folder of test/unit/ (cmake/pe_unit_tests.cmake), of the sources kept above.
include(cmake/pe_unit_tests.cmake)
pe_unit_test_folders(PE_TEST_FOLDERS)
foreach(folder ${PE_TEST_FOLDERS})
  pe_unit_test_sources(${folder} sources)
  set(kept)
  foreach(source ${sources})
    if(source IN_LIST PE_ROS_FREE_TESTS)
      list(APPEND kept ${source})
    endif()
  endforeach()
  if(NOT kept)
    continue()
  endif()
  add_executable(test_${folder} ${kept} test/unit/support/test_main.cpp)
  target_link_libraries(test_${folder} propulsion_estimator_core GTest::gtest)
  target_include_directories(test_${folder} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/support")
  target_compile_definitions(test_${folder} PRIVATE PE_REPO_DIR="${PE_REPO_DIR}")
  # One CTest test per gtest, listed and run through CMAKE_CROSSCOMPILING_EMULATOR (qemu-aarch64).
  gtest_discover_tests(test_${folder} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 120)
endforeach()

find_package(benchmark REQUIRED)
add_executable(bench_estimator test/benchmark/bench_estimator.cpp)
target_link_libraries(bench_estimator propulsion_estimator_estimation benchmark::benchmark)
target_compile_definitions(bench_estimator PRIVATE PE_REPO_DIR="${PE_REPO_DIR}")
