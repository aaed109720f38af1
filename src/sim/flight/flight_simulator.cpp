#include "propulsion_estimator/sim/flight/flight_simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/simulation_error.h"
#include "propulsion_estimator/sim/flight/esc_telemetry_sensor.h"
#include "propulsion_estimator/sim/flight/flight_controller.h"
#include "propulsion_estimator/sim/physics/gaussian_noise.h"
#include "propulsion_estimator/sim/physics/lipo_battery.h"
#include "propulsion_estimator/sim/flight/multirotor_dynamics.h"
#include "propulsion_estimator/sim/flight/vehicle_parts.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/sim/physics/power_train.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// A hover may use at most this share of the rotors' thrust, leaving the rest to attitude control.
constexpr double kMaxHoverThrustShare = 0.8;
constexpr double kEmptyStateOfCharge = 0.02;
// A hover that ends farther than this from its height did not happen as scripted; its manifest
// segment would be wrong.
constexpr double kHoverToleranceM = 0.25;
constexpr int kMinRcOutChannels = 8;  // MAVLink SERVO_OUTPUT_RAW carries 8 (or 16) outputs
// A vehicle whose roll or pitch stays beyond kFlipAngleDeg for kFlipTriggerS has flipped over:
// PX4's failure detector (FD_FAIL_R, FD_FAIL_P, FD_FAIL_R_TTRI) gives up on the attitude there;
// the controller itself tilts at most 20 deg.
constexpr double kFlipAngleDeg = 60.0;
constexpr double kFlipTriggerS = 0.3;

// Readings of one stream at k / rate, k = 0, 1, ...: at the first physics step at or after each.
class Stream {
 public:
  explicit Stream(double rate_hz) : rate_hz_(rate_hz) {}
  bool due(double time_s) {
    if (time_s + 1e-9 < next_ / rate_hz_) return false;
    next_ = static_cast<long>(std::floor(time_s * rate_hz_ + 1e-9)) + 1;
    return true;
  }

 private:
  double rate_hz_;
  long next_ = 0;
};

FlightSetpoint setpointAt(const ScheduledSegment& scheduled, double time_s) {
  const FlightSegment& segment = scheduled.segment;
  const double elapsed = time_s - scheduled.start_s;
  FlightSetpoint setpoint{scheduled.start_height_m, 0.0, false, scheduled.start_position_m, Eigen::Vector2d::Zero()};
  switch (segment.kind) {
    case SegmentKind::kTakeoff:
      if (elapsed < kTakeoffSpinUpS) break;
      setpoint.height_m =
          std::min(scheduled.end_height_m, scheduled.start_height_m + segment.rate_m_s * (elapsed - kTakeoffSpinUpS));
      setpoint.vertical_speed_m_s = setpoint.height_m < scheduled.end_height_m ? segment.rate_m_s : 0.0;
      break;
    case SegmentKind::kClimb:
    case SegmentKind::kDescend: {
      const double direction = scheduled.end_height_m > scheduled.start_height_m ? 1.0 : -1.0;
      const double travelled =
          std::min(std::fabs(scheduled.end_height_m - scheduled.start_height_m), segment.rate_m_s * elapsed);
      setpoint.height_m = scheduled.start_height_m + direction * travelled;
      setpoint.vertical_speed_m_s = direction * segment.rate_m_s;
      break;
    }
    case SegmentKind::kLand:
      // Keeps descending below the ground, so that the controller presses the gear down.
      setpoint.height_m = scheduled.start_height_m - segment.rate_m_s * elapsed;
      setpoint.vertical_speed_m_s = -segment.rate_m_s;
      setpoint.landing = true;
      break;
    case SegmentKind::kMove: {
      const Eigen::Vector2d direction = segment.displacement_m.normalized();
      const double travelled = std::min(segment.displacement_m.norm(), segment.speed_m_s * elapsed);
      setpoint.position_m = scheduled.start_position_m + travelled * direction;
      setpoint.velocity_m_s = segment.speed_m_s * direction;
      break;
    }
    case SegmentKind::kWait:
    case SegmentKind::kHover:
    case SegmentKind::kPayload: break;
  }
  return setpoint;
}

bool airborne(SegmentKind kind) { return kind != SegmentKind::kWait && kind != SegmentKind::kPayload; }

// Refuses a payload whose hover would need more than kMaxHoverThrustShare of the rotors' thrust
// at the autopilot's top pulse width from the battery as it starts.
void checkThrustReserve(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                        const std::vector<ScheduledSegment>& schedule, double vehicle_mass_kg, int rotors,
                        double air_density) {
  const PropulsionChain chain(params.chain);
  const double source_v = params.battery.openCircuitVoltage(profile.vehicle.battery_initial_soc);
  const ChainInput input{escDuty(effects, params.chain.esc, 0, profile.autopilot.pwm_max_us), 0.0,
                         air_density, params.chain.motor.reference_temperature_c};
  const double series_ohm = params.battery.series_resistance_ohm + effects.supply_resistance_ohm.value_or(0.0);
  const double rotor_max_thrust = chain.steadyFromSource(input, source_v, series_ohm, rotors, nullptr).thrust_n;
  const double max_thrust = rotor_max_thrust * airframeThrustShare(effects, rotor_max_thrust);
  int payload_segment = -1;
  for (const ScheduledSegment& scheduled : schedule) {
    if (scheduled.segment.kind == SegmentKind::kPayload) payload_segment = scheduled.index;
    if (!airborne(scheduled.segment.kind)) continue;
    const double mass = vehicle_mass_kg + scheduled.payload_mass_kg;
    const double needed = mass * kStandardGravity / rotors;
    if (needed > kMaxHoverThrustShare * max_thrust) {
      const std::string field =
          payload_segment >= 0 ? "segments[" + std::to_string(payload_segment) + "].mass_kg" : "vehicle.urdf";
      throw ConfigError(profile.source + ": " + field + ": " + formatPrintf("%.3g", mass) + " kg needs " +
                        formatPrintf("%.3g", needed) + " N per rotor, more than " +
                        formatPrintf("%.3g", 100.0 * kMaxHoverThrustShare) + " % of the " +
                        formatPrintf("%.3g", max_thrust) + " N each gives at " +
                        formatNumber(profile.autopilot.pwm_max_us) + " us from " + formatPrintf("%.3g", source_v) +
                        " V");
    }
  }
}

// Refuses a segment that did not end as scripted: a hover away from its height (its manifest
// segment would be wrong), a landing that has not disarmed.
void checkSegmentEnd(const FlightProfile& profile, const ScheduledSegment& scheduled, double height_m, bool armed) {
  const std::string at = profile.source + ": segments[" + std::to_string(scheduled.index) + "].type: ";
  if (scheduled.segment.kind == SegmentKind::kHover &&
      !(std::fabs(height_m - scheduled.end_height_m) <= kHoverToleranceM)) {
    throw SimulationError(at + "the vehicle ended its hover at " + formatPrintf("%.3g", height_m) + " m instead of " +
                          formatPrintf("%.3g", scheduled.end_height_m) + " m");
  }
  if (scheduled.segment.kind == SegmentKind::kLand && armed) {
    throw SimulationError(at + "the vehicle had not landed and disarmed " + formatPrintf("%.3g", kTouchdownS) +
                          " s after its descent");
  }
}

// Roll and pitch in degrees (ZYX Euler angles, as PX4 reports them).
Eigen::Vector2d rollPitchDeg(const Eigen::Quaterniond& attitude) {
  const Eigen::Matrix3d rotation = attitude.toRotationMatrix();
  const double degrees_per_rad = 360.0 / kTwoPi;
  return Eigen::Vector2d(std::atan2(rotation(2, 1), rotation(2, 2)),
                         std::asin(std::clamp(-rotation(2, 0), -1.0, 1.0))) *
         degrees_per_rad;
}

// Refuses a flip (see kFlipAngleDeg): a vehicle lying on its side or back may rest low and still,
// where the land detector would take it for landed. `beyond_since_s` carries the time the
// attitude went beyond the limit from one step to the next.
void checkAttitude(const FlightProfile& profile, const ScheduledSegment& scheduled, const Eigen::Quaterniond& attitude,
                   double time_s, std::optional<double>* beyond_since_s) {
  const Eigen::Vector2d roll_pitch = rollPitchDeg(attitude);
  if (roll_pitch.cwiseAbs().maxCoeff() <= kFlipAngleDeg) {
    beyond_since_s->reset();
    return;
  }
  if (!*beyond_since_s) *beyond_since_s = time_s;
  if (time_s - **beyond_since_s < kFlipTriggerS - 1e-9) return;
  throw SimulationError(profile.source + ": segments[" + std::to_string(scheduled.index) +
                        "].type: the vehicle flipped over: roll " + formatPrintf("%.0f", roll_pitch.x()) +
                        " deg, pitch " + formatPrintf("%.0f", roll_pitch.y()) + " deg at t = " +
                        formatPrintf("%.3f", time_s) + " s, beyond " + formatNumber(kFlipAngleDeg) + " deg since " +
                        formatPrintf("%.3f", **beyond_since_s) + " s");
}

// Everything a flight starts from, once every input has been checked.
struct FlightSetup {
  std::vector<ScheduledSegment> schedule;
  MultirotorDynamics dynamics;
  FlightController controller;
  std::vector<PropulsionChain> chains;  // one per rotor, in motor order
};

// Each rotor's chain: the parameter file's, built with the vehicle's own parts when the profile
// draws them, then the weak propeller's fault. A drawn part the chain refuses names vehicle.parts.
std::vector<PropulsionChain> makeChains(const SimParams& params, const FlightProfile& profile, const Vehicle& vehicle) {
  std::vector<MotorParts> parts;
  if (profile.vehicle.parts) {
    std::vector<int> spins;
    for (const Rotor& rotor : vehicle.rotors) spins.push_back(rotor.spin_direction);
    parts = drawMotorParts(*profile.vehicle.parts, spins);
  }
  std::vector<PropulsionChain> chains;
  for (std::size_t k = 0; k < vehicle.rotors.size(); ++k) {
    ChainParams chain = parts.empty() ? params.chain : withParts(params.chain, parts[k]);
    const std::optional<PropellerFault>& weak = profile.faults.weak_propeller;
    if (weak && weak->motor == static_cast<int>(k) + 1) {
      chain.propeller = weak->damage == PropellerDamage::kWorn ? wornPropeller(chain.propeller, weak->thrust_factor)
                                                               : scaledPropeller(chain.propeller, weak->thrust_factor);
    }
    try {
      chains.emplace_back(chain);
    } catch (const FieldError& e) {
      if (parts.empty()) throw;
      throw ConfigError(profile.source + ": vehicle.parts: motor " + std::to_string(k + 1) + "'s drawn " + e.what());
    }
  }
  return chains;
}

FlightSetup setUpFlight(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                        const Vehicle& vehicle, const FlightSensorParams& sensors) {
  params.validate();
  effects.validate();
  sensors.validate();
  effects.validateEscCount(static_cast<int>(vehicle.rotors.size()));
  // The vehicle's refusals (no mass properties, a rotor layout the mixer cannot use) name its URDF.
  const auto fromUrdf = [&profile](const auto& make) {
    try {
      return make();
    } catch (const ConfigError& e) {
      throw ConfigError(profile.vehicle.urdf_path + ": " + e.what());
    }
  };
  FlightSetup setup{
      scheduleFlight(profile), fromUrdf([&] { return MultirotorDynamics(vehicle, profile.vehicle, profile.cable); }),
      fromUrdf([&] { return FlightController(vehicle, profile.autopilot, profile.vehicle.landing_gear_height_m); }),
      {}};
  const int rotors = static_cast<int>(vehicle.rotors.size());
  if (profile.faults.weak_propeller && profile.faults.weak_propeller->motor > rotors) {
    throw ConfigError(profile.source + ": faults.weak_propeller.motor: " +
                      std::to_string(profile.faults.weak_propeller->motor) + " is not a motor of " +
                      profile.vehicle.urdf_path + " (" + std::to_string(rotors) + " rotors)");
  }
  // The reserve is the intact propellers': a weak one the others cannot balance shows as a flip.
  checkThrustReserve(params, effects, profile, setup.schedule, setup.dynamics.vehicleMassKg(),
                     rotors, effects.air.value_or(params.bench.air).densityKgM3());
  setup.chains = makeChains(params, profile, vehicle);
  return setup;
}

class Noise {
 public:
  explicit Noise(std::uint64_t seed) : rng_(seed) {}
  double operator()(double sigma) { return gaussianNoise(sigma, rng_); }
  Eigen::Vector3d vector(double sigma) { return Eigen::Vector3d((*this)(sigma), (*this)(sigma), (*this)(sigma)); }

 private:
  std::mt19937_64 rng_;
};

// Zero-mean error with standard deviation sigma and correlation time tau, sampled at `rate_hz`:
// e <- a e + sqrt(1 - a^2) sigma n, a = exp(-1 / (rate tau)); starts in its stationary spread.
class GaussMarkov3 {
 public:
  GaussMarkov3(double sigma, double correlation_s, double rate_hz, Noise* noise)
      : sigma_(sigma),
        decay_(std::exp(-1.0 / (rate_hz * correlation_s))),
        noise_(noise),
        error_(noise->vector(sigma)) {}
  const Eigen::Vector3d& next() {
    error_ = decay_ * error_ + std::sqrt(1.0 - decay_ * decay_) * noise_->vector(sigma_);
    return error_;
  }

 private:
  double sigma_;
  double decay_;
  Noise* noise_;
  Eigen::Vector3d error_;
};

// One flight, step by step: the physics, the messages it emits and the manifest it yields.
class FlightRun {
 public:
  FlightRun(const SimParams& params, const SimEffects& effects, const FlightProfile& profile, const Vehicle& vehicle,
            std::uint64_t seed, FlightSink* sink, const FlightSensorParams& sensors)
      : params_(params),
        effects_(effects),
        profile_(profile),
        vehicle_(vehicle),
        sensors_(sensors),
        sink_(sink),
        setup_(setUpFlight(params, effects, profile, vehicle, sensors)),
        rotors_(static_cast<int>(vehicle.rotors.size())),
        air_(effects.air.value_or(params.bench.air)),
        density_(air_.densityKgM3()),
        train_(setup_.chains, effects, air_.temperature_c),
        battery_(params.battery, profile.vehicle.battery_initial_soc),
        noise_(seed),
        origin_(setup_.dynamics.basePosition()),
        current_sign_(profile.autopilot.flavour == AutopilotFlavour::kPx4 ? -1.0 : 1.0),
        avionics_a_(profile.vehicle.avionics_current_a),
        position_error_(sensors.position_sigma_m, sensors.navigation_error_correlation_s, sensors.pose_rate_hz,
                        &noise_),
        velocity_error_(sensors.velocity_sigma_m_s, sensors.navigation_error_correlation_s, sensors.pose_rate_hz,
                        &noise_),
        rc_out_(profile.autopilot.rc_out_rate_hz),
        truth_(profile.autopilot.rc_out_rate_hz),
        battery_stream_(sensors.battery_rate_hz),
        imu_(sensors.imu_rate_hz),
        pose_(sensors.pose_rate_hz),
        pressure_(sensors.pressure_rate_hz),
        air_temperature_(sensors.air_temperature_rate_hz),
        range_(sensors.rangefinder_rate_hz),
        motor_temperature_(sensors.motor_temperature_rate_hz),
        esc_telemetry_(sensors.esc_telemetry_rate_hz > 0.0 ? sensors.esc_telemetry_rate_hz : 1.0),
        // A stream of its own (seed mixed with a constant), so that telemetry leaves the other
        // streams as a flight without it draws them.
        esc_sensor_(sensors, rotors_, profile.autopilot.flavour == AutopilotFlavour::kPx4, seed ^ 0x9e3779b97f4a7c15ULL),
        thrust_(rotors_),
        torque_(rotors_),
        inflows_(rotors_),
        airframe_share_(rotors_, 1.0) {}

  FlightResult fly() {
    const std::vector<ScheduledSegment>& schedule = setup_.schedule;
    MultirotorDynamics& dynamics = setup_.dynamics;
    const long steps = std::lround(schedule.back().end_s / kFlightStepS);
    for (long step = 0; step <= steps; ++step) {
      const double t = step * kFlightStepS;
      const ScheduledSegment& segment = enterSegment(t);
      const NavigationState navigation{dynamics.basePosition(), dynamics.baseVelocity(), dynamics.attitude(),
                                       dynamics.angularVelocityBody()};
      const std::vector<double>& pwm =
          setup_.controller.update(setpointAt(segment, t), navigation, kFlightStepS);
      const PowerTrainState& power = drivePropulsion(pwm, navigation);
      if (sink_) emit(t, pwm, power, navigation);
      advance(step, t, segment, power);
    }
    checkSegmentEnd(profile_, schedule.back(), dynamics.basePosition().z(), setup_.controller.armed());
    FlightResult result;
    result.segments = manifestSegments();
    result.duration_s = steps * kFlightStepS;
    result.final_state_of_charge = battery_.stateOfCharge();
    return result;
  }

 private:
  // The segment at `t`: the ones that ended are checked and left, a new one's action taken.
  const ScheduledSegment& enterSegment(double t) {
    const std::vector<ScheduledSegment>& schedule = setup_.schedule;
    while (current_ + 1 < schedule.size() && t >= schedule[current_].end_s - 1e-9) {
      checkSegmentEnd(profile_, schedule[current_], setup_.dynamics.basePosition().z(), setup_.controller.armed());
      ++current_;
      entered_ = false;
    }
    const ScheduledSegment& segment = schedule[current_];
    if (!entered_) {
      if (segment.segment.kind == SegmentKind::kPayload) setup_.dynamics.setPayload(segment.segment.payload_mass_kg);
      if (segment.segment.kind == SegmentKind::kTakeoff) setup_.controller.arm();
      entered_ = true;
    }
    return segment;
  }

  // The rotors' inflows, the power train's step from the battery, and the thrusts and torques.
  const PowerTrainState& drivePropulsion(const std::vector<double>& pwm, const NavigationState& navigation) {
    MultirotorDynamics& dynamics = setup_.dynamics;
    for (int k = 0; k < rotors_; ++k) {
      const Eigen::Vector3d velocity = dynamics.rotorVelocity(k);
      const Eigen::Vector3d axis = navigation.attitude * vehicle_.rotors[k].thrust_axis;
      const double axial_speed = velocity.dot(axis);
      inflows_[k] = rotorInflow(effects_, train_.chain(k).params().propeller.radiusM(), dynamics.rotorPosition(k).z(),
                                axial_speed, (velocity - axial_speed * axis).norm());
      train_.setInflow(k, inflows_[k]);
    }
    // The avionics load the battery beside the ESCs: the ESCs' supply is the battery's Thevenin
    // source less the avionics' drop across its series resistance.
    const PowerTrainState& power = train_.step(
        pwm, Supply{battery_.sourceVoltage() - battery_.seriesResistanceOhm() * avionics_a_, battery_.seriesResistanceOhm()},
        air_, kFlightStepS);
    for (int k = 0; k < rotors_; ++k) {
      airframe_share_[k] = airframeThrustShare(effects_, power.motors[k].thrust_n);
      thrust_[k] = power.motors[k].thrust_n * airframe_share_[k];
      torque_[k] = power.motors[k].torque_nm;
    }
    return power;
  }

  // The airframe moves; it must stay finite and upright, and the battery must last.
  void advance(long step, double t, const ScheduledSegment& segment, const PowerTrainState& power) {
    MultirotorDynamics& dynamics = setup_.dynamics;
    dynamics.step(thrust_, torque_, density_, kFlightStepS);
    if (!dynamics.isFinite()) {
      throw SimulationError(profile_.source + ": the simulation diverged at t = " +
                            formatPrintf("%.3f", (step + 1) * kFlightStepS) + " s");
    }
    checkAttitude(profile_, segment, dynamics.attitude(), (step + 1) * kFlightStepS, &flipping_since_);
    if (dynamics.touchedGround()) {
      if (ground_contacts_.empty() || ground_contacts_.back().second < t - 0.5 * kFlightStepS) {
        ground_contacts_.emplace_back(t, t);
      }
      ground_contacts_.back().second = t + kFlightStepS;
    }
    battery_.draw(power.current_a + avionics_a_, kFlightStepS);
    if (battery_.stateOfCharge() < kEmptyStateOfCharge) {
      throw SimulationError(profile_.source + ": vehicle.battery_initial_soc: the battery is empty " +
                            formatPrintf("%.3g", t) + " s into the flight");
    }
  }

  // Every stream due at `t`, in a fixed order: the noise is drawn from one generator (ESC telemetry's from its own).
  void emit(double t, const std::vector<double>& pwm, const PowerTrainState& power, const NavigationState& navigation) {
    const double height = navigation.position_m.z();
    const Eigen::Matrix3d rotation = navigation.attitude.toRotationMatrix();
    if (rc_out_.due(t)) {
      RcOutSample sample{t, std::vector<std::uint16_t>(std::max(kMinRcOutChannels, rotors_), 0)};
      for (int k = 0; k < rotors_; ++k) sample.channels[k] = static_cast<std::uint16_t>(pwm[k]);
      sink_->rcOut(sample);
    }
    if (truth_.due(t)) sink_->truth(truthSample(t, pwm, power, navigation));
    if (battery_stream_.due(t)) {
      sink_->battery({t, power.terminal_voltage_v + noise_(sensors_.battery_voltage_sigma_v),
                      current_sign_ * (power.current_a + avionics_a_ + noise_(sensors_.battery_current_sigma_a)),
                      std::round(100.0 * std::clamp(battery_.stateOfCharge(), 0.0, 1.0)) / 100.0});
    }
    if (imu_.due(t)) sink_->imu(imuSample(t, navigation));
    if (pose_.due(t)) {
      sink_->pose({t, navigation.position_m - origin_ + position_error_.next(), navigation.attitude});
      sink_->velocity(
          {t, navigation.velocity_m_s + velocity_error_.next(), rotation * navigation.angular_velocity_body_rad_s});
    }
    if (pressure_.due(t)) {
      sink_->staticPressure({t, air_.pressureAtHeightPa(height) + noise_(sensors_.pressure_sigma_pa),
                             sensors_.pressure_sigma_pa, "base_link"});
    }
    if (air_temperature_.due(t)) {
      sink_->airTemperature({t, air_.temperature_c + noise_(sensors_.air_temperature_sigma_c),
                             sensors_.air_temperature_sigma_c, "base_link"});
    }
    if (range_.due(t)) {
      double reading = rotation(2, 2) > 0.1 ? height / rotation(2, 2) + noise_(sensors_.rangefinder_sigma_m)
                                            : std::numeric_limits<double>::infinity();
      if (reading < sensors_.rangefinder_min_m) reading = -std::numeric_limits<double>::infinity();
      if (reading > sensors_.rangefinder_max_m) reading = std::numeric_limits<double>::infinity();
      sink_->rangefinder(
          {t, reading, sensors_.rangefinder_min_m, sensors_.rangefinder_max_m, sensors_.rangefinder_fov_rad});
    }
    if (motor_temperature_.due(t)) {
      const auto hottest = std::max_element(power.winding_temperature_c.begin(), power.winding_temperature_c.end());
      const std::size_t k = static_cast<std::size_t>(hottest - power.winding_temperature_c.begin());
      sink_->motorTemperature({t, *hottest + noise_(sensors_.motor_temperature_sigma_c),
                               sensors_.motor_temperature_sigma_c, vehicle_.rotors[k].name});
    }
    if (sensors_.esc_telemetry_rate_hz > 0.0 && esc_telemetry_.due(t)) sink_->escTelemetry(esc_sensor_.read(t, power));
  }

  TruthSample truthSample(double t, const std::vector<double>& pwm, const PowerTrainState& power,
                          const NavigationState& navigation) const {
    const MultirotorDynamics& dynamics = setup_.dynamics;
    TruthSample sample;
    sample.time_s = t;
    sample.payload_mass_kg = dynamics.payloadMassKg();
    sample.total_mass_kg = dynamics.vehicleMassKg() + sample.payload_mass_kg;
    sample.cable_tension_n = dynamics.cableTensionN();
    sample.height_m = navigation.position_m.z();
    sample.vertical_speed_m_s = navigation.velocity_m_s.z();
    sample.air_density_kg_m3 = density_;
    sample.density_ratio = density_ / params_.bench.air.densityKgM3();
    sample.battery_voltage_v = power.terminal_voltage_v;
    sample.esc_voltage_v = power.esc_voltage_v;
    sample.battery_current_a = power.current_a + avionics_a_;
    sample.thrust_loss_factor = std::accumulate(airframe_share_.begin(), airframe_share_.end(), 0.0) / rotors_;
    double static_thrust = 0.0, climb_thrust = 0.0;
    for (int k = 0; k < rotors_; ++k) {
      const ChainState& motor = power.motors[k];
      // The inflow effects split as thrust(climb, ground) = static x climb x ground at the rotor's
      // speed: climb (with any edgewise flow) without the ground, the ground on top of the climb.
      const RotorAerodynamics& rotor = train_.chain(k).rotor();
      const double climb =
          rotor.load(motor.omega_rad_s, {inflows_[k].axial_speed_m_s, 1.0, inflows_[k].edgewise_speed_m_s}).thrust;
      const double with_ground = rotor.load(motor.omega_rad_s, inflows_[k]).thrust;
      const double isolated = train_.chain(k).params().propeller.thrustN(density_, motor.omega_rad_s / kTwoPi);
      static_thrust += isolated;
      climb_thrust += isolated * climb;
      sample.motors.push_back({pwm[k], thrust_[k], motor.input_current_a, motor.input_power_w, motor.rpm(),
                               climb > 0.0 ? with_ground / climb : 1.0, climb, power.winding_temperature_c[k],
                               pwm[k] >= params_.bench.sweep_pwm_min_us && pwm[k] <= params_.bench.sweep_pwm_max_us});
    }
    sample.climb_factor = static_thrust > 0.0 ? climb_thrust / static_thrust : 1.0;
    return sample;
  }

  ImuSample imuSample(double t, const NavigationState& navigation) {
    const Eigen::Vector3d tilt = noise_.vector(sensors_.orientation_sigma_rad);
    ImuSample sample;
    sample.time_s = t;
    sample.orientation = tilt.norm() > 0.0
                             ? navigation.attitude * Eigen::Quaterniond(Eigen::AngleAxisd(tilt.norm(), tilt.normalized()))
                             : navigation.attitude;
    sample.angular_velocity_rad_s = navigation.angular_velocity_body_rad_s + noise_.vector(sensors_.gyro_sigma_rad_s);
    sample.linear_acceleration_m_s2 = setup_.dynamics.specificForceBody() + noise_.vector(sensors_.accel_sigma_m_s2);
    sample.orientation_sigma_rad = sensors_.orientation_sigma_rad;
    sample.angular_velocity_sigma_rad_s = sensors_.gyro_sigma_rad_s;
    sample.linear_acceleration_sigma_m_s2 = sensors_.accel_sigma_m_s2;
    return sample;
  }

  std::vector<ManifestSegment> manifestSegments() const {
    // Microseconds and milligrams: enough for any use, and the manifest reads "16.88", not "16.879999999999999".
    const auto micro = [](double value) { return std::round(value * 1e6) / 1e6; };
    std::vector<ManifestSegment> segments;
    for (const ManifestSpan& span : manifestSpans(profile_, setup_.schedule)) {
      // The ground carries part of the weight while a foot or the payload touches it (a descent
      // that overshoots onto the ground): that time is left out, and the settle time after it.
      const double mass = micro(setup_.dynamics.vehicleMassKg() + span.payload_mass_kg);
      double start = span.start_s;
      for (const auto& [from, to] : ground_contacts_) {
        if (to < start || from > span.end_s) continue;
        if (from > start) segments.push_back({micro(start), micro(from), mass});
        start = to + profile_.manifest_settle_s;
      }
      if (start < span.end_s) segments.push_back({micro(start), micro(span.end_s), mass});
    }
    return segments;
  }

  const SimParams& params_;
  const SimEffects& effects_;
  const FlightProfile& profile_;
  const Vehicle& vehicle_;
  const FlightSensorParams& sensors_;
  FlightSink* sink_;
  FlightSetup setup_;
  const int rotors_;
  const AirConditions air_;
  const double density_;
  PowerTrain train_;
  LipoBattery battery_;
  Noise noise_;
  const Eigen::Vector3d origin_;
  const double current_sign_;
  const double avionics_a_;  // drawn from the battery beside the ESCs, A
  GaussMarkov3 position_error_, velocity_error_;
  Stream rc_out_, truth_, battery_stream_, imu_, pose_, pressure_, air_temperature_, range_, motor_temperature_;
  Stream esc_telemetry_;
  EscTelemetrySensor esc_sensor_;
  std::vector<double> thrust_, torque_;
  std::vector<RotorInflow> inflows_;
  std::vector<double> airframe_share_;  ///< each rotor's thrust share the airframe leaves (thrust_loss)
  std::size_t current_ = 0;
  bool entered_ = false;
  std::optional<double> flipping_since_;
  std::vector<std::pair<double, double>> ground_contacts_;  // [from, to] in s, merged step by step
};

}  // namespace

void checkFlight(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                 const Vehicle& vehicle, const FlightSensorParams& sensors) {
  setUpFlight(params, effects, profile, vehicle, sensors);
}

FlightResult simulateFlight(const SimParams& params, const SimEffects& effects, const FlightProfile& profile,
                            const Vehicle& vehicle, std::uint64_t seed, FlightSink* sink,
                            const FlightSensorParams& sensors) {
  return FlightRun(params, effects, profile, vehicle, seed, sink, sensors).fly();
}

}  // namespace sim
}  // namespace propulsion_estimator
