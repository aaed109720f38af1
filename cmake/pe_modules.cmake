# Included by CMakeLists.txt, in the catkin build and in the ROS-free one (PE_ROS_FREE, make arm64).
# --- Modules: one folder, one library. src/<module>/ mirrors include/propulsion_estimator/<module>/,
# and test/unit/package/test_layering.cpp checks which module may include which, and that a module links only
# modules it may include. -----------------------------------------------------------------------------
function(pe_module name folder)
  # A module's own sub-folders too (model/effects: one file per effect); sim/ holds only modules.
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/${folder}/*.cpp")
  list(FILTER sources EXCLUDE REGEX "_main\\.cpp$")
  add_library(${name} ${sources})
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(${name} PUBLIC ${ARGN})
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()

# ROS-free: everything that computes. Links Eigen, yaml-cpp, urdfdom and libcsv only.
pe_module(propulsion_estimator_common common yaml-cpp)
target_include_directories(propulsion_estimator_common PUBLIC ${EIGEN3_INCLUDE_DIR})
pe_module(propulsion_estimator_model model propulsion_estimator_common)
# TinyXML, urdfdom's XML layer (its headers include it), also reads the joints' edges before it.
find_library(TINYXML_LIBRARY tinyxml)
if(NOT TINYXML_LIBRARY)
  message(FATAL_ERROR "TinyXML not found: install libtinyxml-dev (scripts/install_deps.sh)")
endif()
pe_module(propulsion_estimator_vehicle vehicle propulsion_estimator_common ${urdfdom_LIBRARIES} ${TINYXML_LIBRARY})
target_include_directories(propulsion_estimator_vehicle PUBLIC ${urdfdom_INCLUDE_DIRS})
# What runs on the vehicle: the estimator (also replayed offline by gap/) ...
pe_module(propulsion_estimator_estimation estimation
  propulsion_estimator_model propulsion_estimator_vehicle propulsion_estimator_common)
# ... and what only the node uses: rate limiter, tare file, health summary, capability.
pe_module(propulsion_estimator_onboard onboard propulsion_estimator_estimation)
# Bench log formats (libcsv tokenizes them), the flight manifest, the flight streams and the
# flight-log reader interface with its registry of formats.
pe_module(propulsion_estimator_logs logs propulsion_estimator_common)
target_include_directories(propulsion_estimator_logs PRIVATE ${CSV_INCLUDE_DIR})
target_link_libraries(propulsion_estimator_logs PRIVATE ${CSV_LIBRARY})
pe_module(propulsion_estimator_fitting fitting propulsion_estimator_model propulsion_estimator_logs)
# The node's onboard session on a logged flight (estimate, and the gap diagnosis' replays).
pe_module(propulsion_estimator_offline offline propulsion_estimator_onboard propulsion_estimator_logs)
# The gap diagnosis: where the model and weighed flights part, and which effect explains it.
pe_module(propulsion_estimator_gap gap propulsion_estimator_offline)
# The simulator: propulsion physics, the simulated thrust stand, the simulated flight.
pe_module(propulsion_estimator_sim_physics sim/physics propulsion_estimator_common)
pe_module(propulsion_estimator_sim_stand sim/stand propulsion_estimator_sim_physics propulsion_estimator_logs)
pe_module(propulsion_estimator_sim_flight sim/flight
  propulsion_estimator_sim_physics propulsion_estimator_vehicle propulsion_estimator_logs)

# The historical name for downstream CMake code: every ROS-free module.
add_library(propulsion_estimator_core INTERFACE)
target_link_libraries(propulsion_estimator_core INTERFACE
  propulsion_estimator_common propulsion_estimator_model propulsion_estimator_vehicle
  propulsion_estimator_estimation propulsion_estimator_onboard propulsion_estimator_logs
  propulsion_estimator_offline propulsion_estimator_fitting propulsion_estimator_gap propulsion_estimator_sim_physics propulsion_estimator_sim_stand
  propulsion_estimator_sim_flight)
