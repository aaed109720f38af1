#pragma once

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace gap {

/// The battery current a flight's log shows with every motor stopped: what the avionics (flight
/// controller, companion computer, radios, camera) draw beside the ESCs, with the current sensor's
/// own offset. The motors' current surfaces hold neither, so the current view takes it out.
struct GroundDraw {
  double current_a = kNaN;  ///< A, the median of the readings; NaN when too few were taken
  int readings = 0;         ///< battery readings with a current, every motor stopped and settled
};

/// The command at or below which a motor is stopped for `domain`'s model: at most 1000 us and
/// 10 us below the bench's lowest pulse width, where its rotor turned. Disarmed outputs lie there
/// (PX4's 900 us; ArduPilot's MOT_PWM_MIN where the bench started above it); an armed idle lies
/// above 1000 us or at the bench's lowest and spins its rotor.
double stoppedPwmUs(const ModelDomain& domain);

/// Readings a GroundDraw rests on at the least (half a second of a 10 Hz battery topic).
constexpr int kMinGroundDrawReadings = 5;

/// The ground draw of `streams`: the battery readings at which the rc/out frame in force, at most
/// `timeout_s` old, and every frame of the `settle_s` before it hold each of the `motors` commands
/// at or below `stopped_us` (stoppedPwmUs), so that no rotor still spins down. Each reading is
/// signed as the flight's discharge (a sensor reporting it negative, as MAVROS gives PX4's, is
/// negated), so that a sensor's offset at rest keeps its sign. NaN when fewer than
/// kMinGroundDrawReadings.
GroundDraw measureGroundDraw(const FlightStreams& streams, int motors, double stopped_us, double settle_s,
                             double timeout_s);

}  // namespace gap
}  // namespace propulsion_estimator
