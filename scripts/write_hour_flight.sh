#!/bin/sh
# Writes the hour of flight that make bench's diagnose_gap benchmarks simulate (two 30-minute
# flights of this profile): DIR/params.yaml, the thesis' hardware with a pack large enough for half
# an hour of hover (the 4 Ah pack lasts about ten minutes), and DIR/profile.yaml, a PX4 quad with
# rc/out at RC_OUT_RATE_HZ hovering at three heights with a payload on a cable.
# Usage: scripts/write_hour_flight.sh DIR RC_OUT_RATE_HZ
set -eu
repo="$(cd "$(dirname "$0")/.." && pwd)"
dir="$1"
rate_hz="$2"
sed 's/^  capacity_ah: 4.0 .*/  capacity_ah: 24.0/' "$repo/config/sim/e300_dji2212_dji9443.yaml" >"$dir/params.yaml"
grep -q '^  capacity_ah: 24.0$' "$dir/params.yaml"
cat >"$dir/profile.yaml" <<PROFILE
autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, rc_out_rate_hz: $rate_hz}
vehicle:
  urdf: $repo/config/f450_quad.urdf
  centre_of_mass_offset_m: [0.008, -0.005, 0.0]
  landing_gear: {height_m: 0.12, half_width_m: 0.12}
  drag_area_m2: 0.04
  battery_initial_soc: 0.95
payload_cable: {length_m: 1.0, attach_point_m: [0.0, 0.0, -0.04], stiffness_n_per_m: 1000, damping_n_s_per_m: 10}
manifest: {settle_s: 8}
segments:
  - {type: wait, duration_s: 5}
  - {type: takeoff, height_m: 2.0, rate_m_s: 1.0}
  - {type: hover, duration_s: 600}
  - {type: climb, height_m: 5.0, rate_m_s: 1.0}
  - {type: hover, duration_s: 600}
  - {type: descend, height_m: 2.0, rate_m_s: 0.8}
  - {type: hover, duration_s: 575}
  - {type: land, rate_m_s: 0.5}
  - {type: wait, duration_s: 5}
PROFILE
