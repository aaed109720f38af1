# The ROS-free build (PE_ROS_FREE=ON; make arm64 cross-builds it for the Raspberry Pi): the modules
# that compute, their unit tests and the core per-message benchmark, without catkin, so that it
# needs no ROS package for the target architecture. Included by CMakeLists.txt once the libraries
# the modules link are found.
include(cmake/pe_modules.cmake)

# The repository from its real path, for the tests' and the benchmark's data (test/data, config/).
get_filename_component(PE_REPO_DIR "${CMAKE_CURRENT_SOURCE_DIR}" REALPATH)

# Every unit test source but those that need ROS: the ROS layer and the bag reader and writer
# (rcout_codec, esc_telemetry_codec, inline_callback_queue, estimator_params, bag/), the process tests of the
# command-line tools, which link the CLI layer and with it rosbag, the fuzz corpora's replay
# (it decodes RCOut), estimator_node's ldd check, and the log formats' agreement (it writes a bag).
file(GLOB_RECURSE PE_ROS_FREE_TESTS CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/test_*.cpp")
list(FILTER PE_ROS_FREE_TESTS EXCLUDE REGEX
  "/test_(rcout_codec|esc_telemetry_codec|inline_callback_queue|parameter_defaults|no_allocation|bag_flight_sink|flight_bag_reader|bench_tools|diagnose_gap_tool|fuzz_corpus|node_links|log_formats_agree)\.cpp$")
enable_testing()
find_package(GTest REQUIRED)
include(GoogleTest)
add_executable(test_ros_free ${PE_ROS_FREE_TESTS})
target_link_libraries(test_ros_free propulsion_estimator_core GTest::gtest)
target_include_directories(test_ros_free PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/test/unit/support")
target_compile_definitions(test_ros_free PRIVATE PE_REPO_DIR="${PE_REPO_DIR}")
# One CTest test per gtest, listed and run through CMAKE_CROSSCOMPILING_EMULATOR (qemu-aarch64).
gtest_discover_tests(test_ros_free DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 120)

find_package(benchmark REQUIRED)
add_executable(bench_estimator test/benchmark/bench_estimator.cpp)
target_link_libraries(bench_estimator propulsion_estimator_estimation benchmark::benchmark)
target_compile_definitions(bench_estimator PRIVATE PE_REPO_DIR="${PE_REPO_DIR}")
