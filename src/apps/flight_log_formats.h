#pragma once

#include "propulsion_estimator/logs/flight_log_formats.h"

namespace propulsion_estimator {

// The flight-log formats the tools read, each registered once in flight_log_formats.cpp.
const FlightLogFormats& flightLogFormats();

}  // namespace propulsion_estimator
