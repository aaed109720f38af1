#pragma once

namespace propulsion_estimator {
namespace sim {

/// Rates and noise of what a PX4/ArduPilot vehicle streams through MAVROS (the rc/out rate is the
/// profile's). Noise is Gaussian: independent per reading, except the EKF's local position and
/// velocity errors, which are first-order Gauss-Markov processes (correlated from one output to the next).
struct FlightSensorParams {
  /// MAVLink stream rates of a companion-computer link (PX4 "onboard" mode, ArduPilot SRx_*):
  ///@{
  double battery_rate_hz = 1.0;    ///< SYS_STATUS / BATTERY_STATUS
  double imu_rate_hz = 50.0;       ///< ATTITUDE_QUATERNION + HIGHRES_IMU
  double pose_rate_hz = 30.0;      ///< LOCAL_POSITION_NED
  double pressure_rate_hz = 10.0;  ///< SCALED_PRESSURE
  double air_temperature_rate_hz = 1.0;
  double rangefinder_rate_hz = 20.0;  ///< DISTANCE_SENSOR
  double motor_temperature_rate_hz = 1.0;
  ///@}

  /// Power module (PX4 default analog module; ~12-bit ADC): a few tens of mV and ~0.1 A.
  ///@{
  double battery_voltage_sigma_v = 0.02;
  double battery_current_sigma_a = 0.1;
  ///@}
  /// ICM-20689-class IMU: noise density 0.01 deg/s/sqrt(Hz) and 100 ug/sqrt(Hz) over ~100 Hz
  /// bandwidth, raised by airframe vibration to these assumed values; EKF attitude ~0.3 deg.
  ///@{
  double gyro_sigma_rad_s = 0.005;
  double accel_sigma_m_s2 = 0.05;
  double orientation_sigma_rad = 0.005;
  ///@}
  /// EKF local position and velocity (GNSS or vision aided, assumed). An EKF's errors wander
  /// slowly rather than jump from one output to the next: first-order Gauss-Markov processes with
  /// this correlation time.
  ///@{
  double position_sigma_m = 0.02;
  double velocity_sigma_m_s = 0.03;
  double navigation_error_correlation_s = 1.0;
  ///@}
  /// MS5611 barometer at its highest oversampling: 0.012 mbar rms (datasheet); temperature
  /// resolution 0.01 deg C.
  ///@{
  double pressure_sigma_pa = 1.2;
  double air_temperature_sigma_c = 0.05;
  ///@}
  /// TFmini-S class lidar: 0.1-12 m, 2 deg field of view, ~1 cm repeatability indoors.
  ///@{
  double rangefinder_sigma_m = 0.01;
  double rangefinder_min_m = 0.1;
  double rangefinder_max_m = 12.0;
  double rangefinder_fov_rad = 0.035;
  ///@}
  /// Thermistor or IR sensor on the motor bell (assumed).
  double motor_temperature_sigma_c = 0.2;

  /// ESC telemetry (BLHeli_32 class through the autopilot's ESC_TELEMETRY / ESC_STATUS stream); a
  /// rate of 0 flies ESCs without telemetry. The rpm is the electrical rpm in steps of 100 eRPM over
  /// `esc_pole_pairs` (DShot telemetry's resolution) with commutation jitter; the current and
  /// voltage are each ESC's own shunt and divider, with a gain error drawn once per ESC, noise and
  /// MAVLink's 0.01 A / 0.01 V steps; each packet is lost with `esc_dropout_probability` (the
  /// autopilot repeats the last one). Figures assumed from BLHeli_32 ESCs' data and flight logs.
  ///@{
  double esc_telemetry_rate_hz = 10.0;
  int esc_pole_pairs = 7;
  double esc_rpm_sigma = 15.0;  ///< rpm
  double esc_current_sigma_a = 0.15;
  double esc_current_gain_sigma = 0.02;  ///< relative, per ESC
  double esc_current_offset_sigma_a = 0.05;  ///< per ESC
  double esc_voltage_sigma_v = 0.03;
  double esc_voltage_gain_sigma = 0.005;  ///< relative, per ESC
  double esc_dropout_probability = 0.03;
  ///@}

  /// Throws FieldError naming the member for a rate outside 0..500 Hz (esc_telemetry_rate_hz:
  /// 0..500), a negative sigma, pole pairs outside 1..30, a dropout probability outside 0..0.9, or a
  /// rangefinder range that is empty.
  void validate() const;
};

}  // namespace sim
}  // namespace propulsion_estimator
