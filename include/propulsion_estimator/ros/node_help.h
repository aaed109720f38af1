#pragma once

namespace propulsion_estimator {

/// Whether `argv` asks for --help (or -h): then estimator_node's help, where its settings are, is
/// printed on stdout, with no ROS master needed. Throws nothing.
bool answeredHelp(int argc, char** argv);

}  // namespace propulsion_estimator
