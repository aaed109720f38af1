# find_package(yaml-cpp) when cross-compiling for arm64 (cmake/aarch64-linux-gnu.cmake points here).
# Debian's libyaml-cpp-dev is not Multi-Arch: same, so its arm64 build cannot be installed beside
# the host's one that the ROS build needs. Its headers are architecture-independent and the host's
# serve; this imports the arm64 runtime library (libyaml-cpp0.7:arm64) as the target `yaml-cpp`.
find_library(YAML_CPP_ARM64_LIBRARY NAMES libyaml-cpp.so.0.7)
if(NOT YAML_CPP_ARM64_LIBRARY OR NOT EXISTS /usr/include/yaml-cpp/yaml.h)
  set(yaml-cpp_FOUND FALSE)
  set(yaml-cpp_NOT_FOUND_MESSAGE
    "needs libyaml-cpp0.7:arm64 and libyaml-cpp-dev (scripts/install_arm64_deps.sh)")
  return()
endif()
if(NOT TARGET yaml-cpp)
  add_library(yaml-cpp SHARED IMPORTED)
  set_target_properties(yaml-cpp PROPERTIES IMPORTED_LOCATION "${YAML_CPP_ARM64_LIBRARY}")
endif()
