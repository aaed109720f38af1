#pragma once

#include <array>
#include <string>
#include <vector>

#include "propulsion_estimator/gap/ground_draw.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/model_effects.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace gap {

/// A short stretch of a weighed segment (block_s long), averaged: the unit the diagnosis fits
/// and scores. Averaging over a block filters the payload's swing and the motors' lag alike in
/// the measured force and in the model's inputs.
struct Block {
  int flight = 0;   ///< index in the flights given
  int segment = 0;  ///< index in its flight's segments
  int group = 0;    ///< consecutive blocks of one segment share a group (the permutation test's unit)
  double time_s = 0.0;         ///< middle of the block, on the flight's clock
  double flight_time_s = 0.0;  ///< since the flight's first weighed segment began
  double mass_kg = 0.0;  ///< kg, vehicle plus payload as weighed
  std::array<double, kMaxMotors> pwm_us{};  ///< per motor, mean over the block, us
  std::array<double, kMaxMotors> axis_up{};  ///< vertical component of each rotor's thrust axis
  double voltage_v = 0.0;  ///< mean battery voltage, V
  /// The motors' share of the battery discharge current, A: the battery's less the flight's ground
  /// draw where the log shows one (the effects' kBatteryCurrent signal keeps the battery's); NaN
  /// without a current sensor.
  double current_a = 0.0;
  /// per motor, mean mechanical speed from ESC telemetry, rpm; NaN without telemetry of it over at
  /// least half the block
  std::array<double, kMaxMotors> rpm{};
  double specific_force_up_m_s2 = 0.0;  ///< vertical specific force (g + vertical acceleration)
  double truth_n = 0.0;          ///< mass x specific_force_up: the vertical thrust that flew
  effects::Signals signals;      ///< height, vertical, horizontal and axial speed, air density, motor temperature; NaN if missing
  double altitude_m = 0.0;       ///< local position z; NaN if missing
  bool hover = false;            ///< steady: slow vertical speed, steady commands
  /// How far the collective (mean over motors) PWM moved within the block, us, whatever the log's
  /// rate: its least-squares trend's change across the block (beyond two standard errors of the
  /// slope) plus 3.7 standard deviations of its noise about the trend (the range 20 frames of noise
  /// span on average)
  double pwm_change_us = 0.0;
  double accel_up_m_s2 = 0.0;    ///< vertical acceleration, specific_force_up minus g
};

/// How flights are cut into blocks.
struct BlockConfig {
  int motors = 4;  ///< rotors, in rotor order
  double block_s = 1.0;  ///< s; length of a block
  double group_s = 10.0;  ///< s; consecutive blocks within this long form one group
  double signal_timeout_s = 1.0;  ///< s; an older reading of a signal counts as missing
  double hover_max_vertical_speed_m_s = 0.2;  ///< m/s; a block slower than this vertically is a hover
  /// s; the rotors' first-order spin-up lag (RotorLag): each motor's pulse width is averaged
  /// through it, so that a block's model thrust is the one the rotors gave; 0: no lag modelled.
  double rotor_time_constant_s = 0.0;
  /// The model's domain: with `outside: reject` a block outside it is left out (and counted), as
  /// the node refuses it; a motor commanded at or below stoppedPwmUs(domain) is stopped, and the
  /// battery current with every motor stopped is the flight's ground draw (measureGroundDraw),
  /// taken out of each block's current. The default, an empty box, stops no command.
  ModelDomain domain;
};

/// Whether a block is quasi-steady: its collective PWM changed by at most `max_pwm_change_us`
/// and it accelerated vertically by at most `max_accel_m_s2`. The surfaces are steady-state maps:
/// while the rotors spin up or down, the thrust lags the PWM by the rotor's time constant, a gap
/// no effect in the library describes.
bool isQuasiSteady(const Block& block, double max_pwm_change_us, double max_accel_m_s2);

/// The result of cutting one flight: its blocks, why a segment gave none, and what was assumed.
struct FlightBlocks {
  std::vector<Block> blocks;  ///< in time order
  /// One line for each segment (or the whole flight) that gave no block, with why and the counts
  /// ("f.bag: segment 2 (15-30 s) lies outside the log's rc/out span 0.00-20.00 s").
  std::vector<std::string> skipped;
  std::vector<std::string> assumptions;  ///< one line for each thing assumed in place of what is missing (no IMU)
  bool has_imu = false;  ///< whether the flight had an IMU
  bool has_current = false;  ///< whether the flight had a battery current
  int frames_without_battery = 0;  ///< rc/out frames in segments with no battery voltage within the timeout
  int blocks_without_attitude = 0;  ///< blocks left out: some frame had no attitude within the timeout
  int blocks_rejected_outside = 0;  ///< blocks left out: outside the domain of a model that rejects them
  GroundDraw ground_draw;  ///< the battery current with every motor stopped, taken out of the blocks' current
};

/// Whether every motor's inputs (pulse width, voltage) lie in `domain`.
bool insideDomain(const Block& block, const ModelDomain& domain, int motors);

/// Cuts `flight` into blocks inside its weighed segments, its commands through the rotor lag. A segment outside the log's time span,
/// or with no rc/out and battery inside it, is listed in `skipped`. Without IMU the
/// vertical specific force is taken as g (level, unaccelerated flight), and said so.
FlightBlocks cutIntoBlocks(const Flight& flight, int flight_index, const Vehicle& vehicle, const BlockConfig& config,
                           int first_group);

}  // namespace gap
}  // namespace propulsion_estimator
