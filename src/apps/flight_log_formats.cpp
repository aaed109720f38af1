#include "flight_log_formats.h"

#include "propulsion_estimator/bag/flight_bag_reader.h"
#include "propulsion_estimator/logs/crazyflie_flight_reader.h"
#include "propulsion_estimator/logs/dataflash_flight_reader.h"
#include "propulsion_estimator/logs/ulog_flight_reader.h"

namespace propulsion_estimator {

const FlightLogFormats& flightLogFormats() {
  static const FlightLogFormats kFormats = [] {
    FlightLogFormats formats;
    // One line per format: its reader tells it from the file's first bytes.
    formats.add(flightBagFormat());
    formats.add(ulogFormat());
    formats.add(dataflashFormat());
    formats.add(crazyflieUsdFormat());
    return formats;
  }();
  return kFormats;
}

}  // namespace propulsion_estimator
