#!/usr/bin/env python3
"""Validates diagnose_gap on simulated flights whose effect is withheld from it.

For each case: a clean bench sweep is simulated and fitted with fit_surfaces (the model), then
several flights of random payloads, heights, climbs, straight legs out and back, descents near the
ground and battery charges are simulated with the case's effects switched on at random magnitudes from realistic ranges (or
with none, or with a fault the library does not hold), and diagnose_gap gets the model, the URDF
and the flights' manifest, without being told what was switched on. The case scores right when
the selected effects are exactly the injected ones (none for a null case and for a fault), and a
weak propeller's motor is the suspect.

With --family each case's hardware and vehicle are drawn (draw_family), down to each motor's own
parts (the profiles' vehicle.parts: propeller coefficients, Kv and ESC end points scattered from
motor to motor, one spin direction's propellers turning more torque per thrust), and each flight
hangs its payload a few millimetres off the attach point the diagnosis is told; the null and
weak-propeller cases also fly three healthy flights of the same vehicle, which diagnose_gap gets
as --reference.

Usage: validate_gap.py --bin DIR --repo DIR --work DIR [--cases N] [--quick] [--seed S] [--case K,...]
                       [--markdown FILE] [--junit FILE] [--jobs N] [--reuse] [--compare-rpm-view]
  --bin      folder holding simulate, fit_surfaces and diagnose_gap
  --quick    one case of each kind the CI needs (null, thrust loss, supply resistance, weak propeller)
  --case     only these of the seed's cases (numbers), drawn as in the whole run
  --markdown write the table (docs/VALIDATION.md)
  --reuse    diagnose the cases already simulated in --work again (after a change to the diagnosis);
             cases not simulated there count as errors
  --compare-rpm-view  diagnose each case also without ESC telemetry's RPM view (--no-rpm-view) and
             count the cases right with and without it; fewer right with it fails the run
  --compare-whole-flights  diagnose each case also as a user without hand-cut segments gives it
             (whole.manifest.yaml: each flight's mass_kg per airborne stretch, the stretches found in
             its log) and count the cases named alike; fewer right that way fails the run

Prints a confusion matrix and the mean held-out shrink; exits 1 when the acceptance thresholds of
issue 8 are missed (>= 90 % right, no null case named, weak propellers located, >= 70 % shrink).
"""
import argparse
import concurrent.futures
import datetime
import math
import os
import platform
import random
import subprocess
import sys

import yaml



def known_effects(bin_dir):
    """The effects the diagnosis knows, from its registry (diagnose_gap --list-effects)."""
    out = subprocess.run([os.path.join(bin_dir, "diagnose_gap"), "--list-effects"], check=True,
                         stdout=subprocess.PIPE, universal_newlines=True).stdout
    return [line.strip() for line in out.splitlines() if line.strip()]


def draw_air(rng):
    """A high or hot site: 1500-3000 m, or a hot day at sea level."""
    if rng.random() < 0.7:
        return {"temperature_c": round(rng.uniform(5, 30), 1), "pressure_pa": round(rng.uniform(70000, 85000))}
    return {"temperature_c": round(rng.uniform(35, 45), 1), "pressure_pa": round(rng.uniform(99000, 102000))}


# How the simulator injects each effect the diagnosis knows: its effects-file entry at a realistic
# random magnitude. The names come from diagnose_gap --list-effects; one missing here is refused.
SIMULATED = {
    "supply_resistance": lambda rng: {"ohm": round(rng.uniform(0.03, 0.08), 4)},
    "air_density": draw_air,
    "ground_effect": lambda rng: {"strength": round(rng.uniform(0.8, 1.6), 3)},
    "thrust_loss": lambda rng: {"fraction": round(rng.uniform(0.03, 0.10), 4)},
    "motor_temperature": lambda rng: {"thermal_resistance_c_per_w": round(rng.uniform(4.0, 10.0), 2)},
    "climb_inflow": lambda rng: {"strength": round(rng.uniform(0.8, 1.6), 3)},
    "esc_offset": lambda rng: {"us": round(rng.choice([-1, 1]) * rng.uniform(15, 40), 1)},
    "translational_lift": lambda rng: {"strength": round(rng.uniform(0.7, 1.3), 3)},
}


def draw_effect(name, rng):
    """The simulator's effects-file entry for one effect at a realistic random magnitude."""
    return SIMULATED[name](rng)


def draw_family(seed, attempt=0):
    """One member of the randomized family: the case's hardware and vehicle drawn around the thesis
    quad, for its bench sweep and its flights alike, so that the diagnosis meets physics it was not
    tuned on (ESC end points and bridge resistance, motor Kv, winding resistance, no-load current,
    magnet and thermal coefficients, propeller thrust and torque coefficients drawn independently,
    battery resistances; drag, centre of gravity and the avionics' own current draw).
    Its own random stream: the cases drawn from --seed are the same with or without the family.
    A later attempt draws again, for a member that cannot fly its own flights.
    The battery's sub-model family (open-circuit curve shape, RC pairs) is issue 19's, in
    sim/physics: once it is in main, it is drawn here too."""
    rng = random.Random(seed * 7919 + 17 + attempt * 104729)
    scale = lambda low, high: rng.uniform(low, high)  # noqa: E731
    hardware = {
        "esc": {"pwm_zero_us": round(1071 + rng.uniform(-25, 25), 1), "pwm_full_us": round(1957 + rng.uniform(-20, 20), 1),
                "resistance_ohm": round(0.02 * scale(0.5, 2.0), 4)},
        "motor": {"kv_rpm_per_v": round(920 * scale(0.94, 1.06), 1),
                  "winding_resistance_ohm": round(0.21 * scale(0.75, 1.35), 4),
                  "no_load_current_a": round(0.81 * scale(0.7, 1.4), 3),
                  "flux_temperature_coefficient_per_c": round(rng.uniform(-0.0013, -0.0009), 5),
                  "thermal_resistance_c_per_w": round(0.52 * scale(0.7, 1.5), 3)},
        "propeller": {"thrust_coefficient": round(0.0807 * scale(0.93, 1.07), 5),
                      "torque_coefficient": round(0.00445 * scale(0.9, 1.1), 6),
                      "solidity": round(0.09 * scale(0.85, 1.15), 4)},
        "battery": {"series_resistance_ohm": round(0.015 * scale(0.6, 2.0), 4),
                    "rc_resistance_ohm": round(0.010 * scale(0.5, 2.0), 4),
                    "rc_capacitance_f": round(3000 * scale(0.5, 2.0))},
    }
    angle = rng.uniform(0, 2 * math.pi)
    # Within the old suite's 10 mm, on the F450's own landing gear.
    radius = rng.uniform(0.0, 0.010)
    vehicle = {"drag_area_m2": round(rng.uniform(0.02, 0.08), 3),
               "centre_of_mass_offset_m": [round(radius * math.cos(angle), 4), round(radius * math.sin(angle), 4), 0.0],
               "avionics_current_a": round(rng.uniform(0.2, 2.0), 2)}
    # The vehicle's own parts (the profile's vehicle.parts): each motor's propeller coefficients,
    # Kv and ESC end points drawn around the hardware's from the vehicle's seed, the same on every
    # flight of the vehicle, and propellers of one spin direction turning more torque per thrust
    # than the other's (real Crazyflies carry 3-6 points more of the thrust on one diagonal).
    # Drawn last, so that the rest of the member is drawn as before.
    vehicle["parts"] = {"seed": rng.randrange(1, 10**9),
                        "thrust_coefficient_spread": round(rng.uniform(0.01, 0.04), 4),
                        "torque_coefficient_spread": round(rng.uniform(0.01, 0.04), 4),
                        "kv_spread": round(rng.uniform(0.01, 0.02), 4),
                        "esc_end_point_spread_us": round(rng.uniform(3.0, 10.0), 1),
                        "spin_torque_ratio": round(rng.uniform(1.0, 1.08), 4)}
    return hardware, vehicle


# The family's world beside the case's effect (issue 33, point 2): what a real vehicle always has,
# at a strength that never needs naming, and the case's effect on top of it (an effect of the same
# kind replaces its background).
BACKGROUND_STRENGTH = (0.0, 0.25)  # ground effect, climb inflow, translational lift: at most a
#                                    quarter of physics' full strength (the case's draw 0.7-1.6)
DAY_AIR = {"temperature_c": (13.0, 23.0), "pressure_pa": (100300, 102300)}  # the day's air, +-3 % density


def background_effects(case_seed, flight_name, hardware):
    """The effects every flight of a family case's vehicle has, case and reference flights alike:
    weak ground effect, climb inflow and translational lift (the vehicle's, drawn once per case),
    its motors warming through their own cooling (the hardware's thermal resistance), and the day's
    air (drawn per flight). Streams of their own: the rest of the case is drawn as without them."""
    vehicle = random.Random("background-%d" % case_seed)
    out = {name: {"strength": round(vehicle.uniform(*BACKGROUND_STRENGTH), 3)}
           for name in ("ground_effect", "climb_inflow", "translational_lift")}
    out["motor_temperature"] = {"thermal_resistance_c_per_w": hardware["motor"]["thermal_resistance_c_per_w"]}
    day = random.Random("day-%s-%d" % (flight_name, case_seed))
    out["air_density"] = {"temperature_c": round(day.uniform(*DAY_AIR["temperature_c"]), 1),
                          "pressure_pa": round(day.uniform(*DAY_AIR["pressure_pa"]))}
    return out


# What the Markdown section says of the world beyond the parts.
WORLD_MESSY = (" and, on every flight, case and reference alike, background physics at up to a quarter of its "
               "strength (ground effect, climb inflow, translational lift), the motors warming through their own "
               "cooling and the day's air (13-23 C, 100.3-102.3 kPa), the case's effect on top with its law drawn "
               "from a family of forms (a supply resistance rising with the current, a thrust loss following each "
               "rotor's loading, ESCs each with its own offset, gain and dead band); weak propellers at 90-94 % of "
               "their thrust (`--plain-world`: without these)")
WORLD_PLAIN = " (`--plain-world`: no background physics, the effects' plain laws, weak propellers at 80-90 %)"


def law_forms(effects, case_seed, rotors=4):
    """The case's effects with their laws drawn from a family of forms (the simulator's effects
    file), so that no correction fits its truth exactly: a supply path whose resistance rises with
    the current, a thrust loss that follows each rotor's loading, ESCs each with its own offset,
    gain and dead band. The same forms on every flight of the case (one vehicle); a stream of its own."""
    forms = random.Random("forms-%d" % case_seed)
    out = {name: dict(params) for name, params in effects.items()}
    if "supply_resistance" in out:
        out["supply_resistance"]["current_coefficient_per_a"] = round(forms.uniform(0.0, 0.015), 4)
    if "thrust_loss" in out:
        out["thrust_loss"].update(load_exponent=round(forms.uniform(-0.5, 1.0), 3), reference_thrust_n=3.3)
    if "esc_offset" in out:
        out["esc_offset"].update(per_esc_us=[round(forms.uniform(-8.0, 8.0), 1) for _ in range(rotors)],
                                 gain=round(forms.uniform(0.97, 1.03), 4), dead_band_us=round(forms.uniform(0.0, 8.0), 1))
    return out


def family_params(base_path, hardware, out_path):
    """The thesis parameter file with the drawn hardware written over it."""
    with open(base_path) as handle:
        params = yaml.safe_load(handle)
    for section, values in hardware.items():
        params[section].update(values)
    with open(out_path, "w") as handle:
        yaml.safe_dump(params, handle, default_flow_style=None)


def effects_file(effects, rng):
    """The effects section of a flight: per-flight air for air_density (sites differ day to day)."""
    out = {}
    for name, params in effects.items():
        if name == "air_density":
            out[name] = {"temperature_c": round(params["temperature_c"] + rng.uniform(-8, 8), 1),
                         "pressure_pa": round(params["pressure_pa"] + rng.uniform(-3000, 3000))}
        else:
            out[name] = dict(params)
    return out


def flight_profile(rng, urdf, fault, vehicle=None, legs=None):
    """A flight of two lifts: take-off, hover, a straight leg out and back, climb, hover, descent to
    near the ground, hover, land; then a new payload and again. Weighed spans cover the whole
    airborne time. The legs (2-5 m/s, 12-30 m, any heading) are drawn from `legs`, a stream of
    their own, so that the rest of a flight is drawn as before they were flown."""
    segments = [{"type": "wait", "duration_s": 3}]
    payloads = [0.0, round(rng.uniform(0.08, 0.22), 3)]
    if rng.random() < 0.5:
        payloads.reverse()
    for lift, payload in enumerate(payloads):
        if lift or payload > 0:
            segments.append({"type": "payload", "mass_kg": payload, "duration_s": 3})
        low = round(rng.uniform(1.5, 2.5), 2)
        # Climbs and descents long enough for a few seconds at steady vertical speed.
        high = round(rng.uniform(6.0, 9.0), 2)
        # Near the ground for ground effect: the empty vehicle down to 0.2 m; with a payload on its
        # 0.15 m cable the simulator needs 0.39 m so that the payload stays clear of the ground.
        near = round(rng.uniform(0.42, 0.6) if payload > 0 else rng.uniform(0.2, 0.3), 2)
        segments += [
            {"type": "takeoff", "height_m": low, "rate_m_s": 1.0},
            {"type": "hover", "duration_s": round(rng.uniform(15, 25))},
        ]
        if legs:
            heading = legs.uniform(0, 2 * math.pi)
            distance = legs.uniform(12, 30)
            east, north = round(distance * math.cos(heading), 2), round(distance * math.sin(heading), 2)
            speed = round(legs.uniform(2, 5), 2)
            segments += [{"type": "move", "east_m": east, "north_m": north, "speed_m_s": speed},
                         {"type": "hover", "duration_s": 4},
                         {"type": "move", "east_m": -east, "north_m": -north, "speed_m_s": speed}]
        segments += [
            {"type": "climb", "height_m": high, "rate_m_s": round(rng.uniform(0.8, 1.5), 2)},
            {"type": "hover", "duration_s": round(rng.uniform(10, 20))},
            {"type": "descend", "height_m": near, "rate_m_s": round(rng.uniform(0.8, 1.5), 2)},
            {"type": "hover", "duration_s": round(rng.uniform(12, 20))},
            {"type": "land", "rate_m_s": 0.6},
        ]
    segments.append({"type": "wait", "duration_s": 2})
    offset = [0.008, -0.005, 0.0]
    if fault and fault.get("cg_offset_m"):
        offset = fault["cg_offset_m"]
    profile = {
        "autopilot": {"flavour": "px4", "pwm_min_us": 1100, "pwm_max_us": 1950, "disarmed_pwm_us": 900,
                      "rc_out_rate_hz": 20},
        "vehicle": {"urdf": urdf, "centre_of_mass_offset_m": offset,
                    "landing_gear": {"height_m": 0.12, "half_width_m": 0.12}, "drag_area_m2": 0.04,
                    "battery_initial_soc": round(rng.uniform(0.8, 1.0), 2)},
        "payload_cable": {"length_m": 0.15, "attach_point_m": [0.0, 0.0, -0.04], "stiffness_n_per_m": 1000,
                          "damping_n_s_per_m": 10},
        "manifest": {"settle_s": 4, "spans": "airborne"},
        "segments": segments,
    }
    if vehicle:
        profile["vehicle"].update(vehicle)
        if fault and fault.get("cg_offset_m"):
            profile["vehicle"]["centre_of_mass_offset_m"] = fault["cg_offset_m"]
    if fault and fault.get("weak_propeller"):
        profile["faults"] = {"weak_propeller": fault["weak_propeller"]}
    return profile


# How far (m, in x and in y) the family's payload is hung from the attach point it is weighed at:
# a hook is never quite where the drawing puts it, and differs from flight to flight.
ATTACH_SCATTER_M = 0.004
# Healthy flights of the same vehicle flown for diagnose_gap --reference: in the family every case
# has them (a user diagnoses a change from the same vehicle's healthy flights: its parts differ from
# the bench unit's as much as the smaller effects do), flown as the vehicle was built (its centre of
# gravity offset too) without the case's effect or weak propeller; in the fixed suite the null and
# weak-propeller cases. The null, centre-of-gravity and weak-propeller cases are also diagnosed
# without them, for the motor verdicts a user without a reference gets.
REFERENCE_FLIGHTS = 3
REFERENCE_LABELS = ("null", "weak_propeller")
NO_REFERENCE_LABELS = ("null", "cg_offset", "weak_propeller")


def scatter_attach_point(profile, rng):
    """The family's payload hung within ATTACH_SCATTER_M of the profile's attach point in x and y."""
    point = profile["payload_cable"]["attach_point_m"]
    profile["payload_cable"]["attach_point_m"] = [round(point[0] + rng.uniform(-ATTACH_SCATTER_M, ATTACH_SCATTER_M), 4),
                                                  round(point[1] + rng.uniform(-ATTACH_SCATTER_M, ATTACH_SCATTER_M), 4),
                                                  point[2]]


def wants_reference(case, args):
    """Whether the case is diagnosed against healthy flights of its vehicle (--reference): without
    one, a weak propeller is named only beyond the spread healthy vehicles show, in every mode."""
    return args.family or case["label"] in REFERENCE_LABELS


def run(command, log):
    with open(log, "a") as handle:
        handle.write("$ " + " ".join(command) + "\n")
        handle.flush()
        return subprocess.run(command, stdout=handle, stderr=subprocess.STDOUT).returncode


# A drawn member that cannot hover its flights' payloads with a margin is refused by the simulator
# ("... more than 80 % of the ... N each gives ..."), and so is one whose hover, with its effects
# and sensors, ends away from its height ("... ended its hover at ..."; its controller did not hold
# the profile): no user flies such a vehicle through such a profile, so it is drawn again. The
# fixed suite has one vehicle, the thesis quad: there the flights (payloads, charges) are drawn again.
# A family member whose drawn parts make a propeller the simulator refuses ("vehicle.parts: motor k's
# drawn propeller.torque_coefficient: ... figure of merit ...") is drawn again too, and so is one
# whose controller loses its attitude ("the vehicle flipped over": a supply resistance sagging its
# motors into saturation on a climb; fresh seeds 556990 and 86038, case 26).
# A family case that none of DRAWS members can fly (fresh seed 900001 case 22: 1.5 kg under an
# 8.6 % thrust loss and a sagging supply) is drawn DRAWS times more with its flights drawn again too,
# and one that none of those flies either (fresh seed 79245 case 2: a 0.079 ohm supply path rising
# 1.2 % per ampere sagged every member away from its hovers) DRAWS times more with its effects'
# magnitudes drawn again as well: the same kinds of effect, so that a seed keeps its 44 cases.
UNFLYABLE = ("more than 80 % of", "ended its hover at", "'s drawn propeller", "the vehicle flipped over")
DRAWS = 10


def run_case(case, args):
    """Simulates, fits and diagnoses one case; returns its row. A case its vehicle cannot fly is
    drawn again, up to DRAWS times: the family member's hardware, or in the fixed suite its flights;
    the family then DRAWS times more, its flights drawn again as well, and DRAWS times more with its
    effects' magnitudes drawn again too (the row gives the effects flown)."""
    for attempt in range(3 * DRAWS if args.family else DRAWS):
        if attempt >= 2 * DRAWS:
            rng = random.Random("effects-%d-%d" % (case["seed"], attempt))
            case = dict(case, effects={name: draw_effect(name, rng) for name in case["effects"]})
        row = run_case_once(case, args, attempt)
        if row.get("unflyable") is None:
            return row
    return dict(row, error="no flyable vehicle in %d draws (see %s)" % (attempt + 1, row["unflyable"]))


def run_case_once(case, args, attempt):
    """run_case's draw number `attempt` (0: the case's own hardware and flights)."""
    # The first draw's flights are the case's own; the fixed suite draws its flights again on a
    # later attempt (the family draws its hardware again and keeps them, up to DRAWS attempts).
    own_flights = attempt == 0 or (args.family and attempt < DRAWS)
    rng = random.Random(case["seed"] if own_flights else "%d-%d" % (case["seed"], attempt))
    case["esc_each"] = args.family and not args.plain_world and "esc_offset" in case["effects"]
    folder = os.path.join(args.work, case["name"])
    os.makedirs(folder, exist_ok=True)
    log = os.path.join(folder, "log.txt")
    params = os.path.join(args.repo, "config/sim/e300_dji2212_dji9443.yaml")
    urdf = os.path.join(args.repo, "config/f450_quad.urdf")
    tool = lambda name: os.path.join(args.bin, name)  # noqa: E731
    bench = os.path.join(folder, "bench.csv")
    model = os.path.join(folder, "model.yaml")
    manifest = os.path.join(folder, "flights.manifest.yaml")
    reference = os.path.join(folder, "reference.manifest.yaml")
    drawn = os.path.join(folder, "family.yaml")
    if args.reuse:
        # Only what was simulated: a case whose simulation failed stays failed (see its log), unless
        # --simulate-missing tries it again. Its family member is the one it was flown with.
        simulated = os.path.exists(manifest) and os.path.exists(model)
        if not simulated and not args.simulate_missing:
            return dict(case, error="not simulated in --work (see %s)" % log)
        if simulated and args.family and os.path.exists(drawn):
            with open(drawn) as handle:
                case["family"] = yaml.safe_load(handle)
            # A case flown with its effects drawn again: those are its truth.
            case["effects"] = case["family"].get("effects", case["effects"])
        if simulated and wants_reference(case, args) and not os.path.exists(reference):
            if not args.simulate_missing:
                return dict(case, error="simulated without its reference flights (see %s)" % log)
            simulated = False
        if simulated and args.simulate_only:
            return dict(case, simulated=True)
        if simulated:
            return diagnose_and_score(case, args, folder, model, manifest, log)
    vehicle = None
    if args.family:
        hardware, vehicle = draw_family(case["seed"], attempt)
        case["family"] = dict(hardware, vehicle=vehicle, draws=attempt + 1)
        if attempt >= 2 * DRAWS:
            case["family"]["effects"] = case["effects"]
        family_params(params, hardware, os.path.join(folder, "params.yaml"))
        params = os.path.join(folder, "params.yaml")
    if run([tool("simulate"), "bench", "--params", params, "--experiment", "pwm_sweep", "--seed", str(case["seed"]),
            "--output", bench], log) or run([tool("fit_surfaces"), bench, "--out", model], log):
        return dict(case, error="bench or fit failed (see %s)" % log)
    # The case's flights, then (wants_reference) healthy flights of the same vehicle: no fault, no
    # effect, their own draws and flight seeds (seed * 100 + 50 + i, apart from every case's own).
    plan = [("flight_%d" % (f + 1), rng, random.Random("legs-%d-%d" % (case["seed"], f)), case.get("fault"),
             case["effects"], case["seed"] * 100 + f, manifest) for f in range(case["flights"])]
    if wants_reference(case, args):
        built = case["fault"] if case["label"] == "cg_offset" else None
        plan += [("reference_%d" % (i + 1), random.Random("reference-%d-%d" % (case["seed"], i)),
                  random.Random("reference-legs-%d-%d" % (case["seed"], i)), built, {}, case["seed"] * 100 + 50 + i,
                  reference) for i in range(REFERENCE_FLIGHTS)]
    manifests = {manifest: []}
    for name, flight_rng, legs, fault, effects, flight_seed, into in plan:
        stem = os.path.join(folder, name)
        profile = flight_profile(flight_rng, urdf, fault, vehicle, legs)
        if args.family:
            scatter_attach_point(profile, random.Random("attach-%s-%d" % (name, case["seed"])))
        with open(stem + ".profile.yaml", "w") as handle:
            yaml.safe_dump(profile, handle, default_flow_style=None)
        command = [tool("simulate"), "flight", "--params", params, "--profile", stem + ".profile.yaml",
                   "--seed", str(flight_seed), "--bag", stem + ".bag", "--manifest", stem + ".manifest.yaml"]
        flown = effects_file(effects, flight_rng) if effects else {}
        if args.family and not args.plain_world:
            flown = dict(background_effects(case["seed"], name, case["family"]), **law_forms(flown, case["seed"]))
        if flown:
            with open(stem + ".effects.yaml", "w") as handle:
                yaml.safe_dump(flown, handle, default_flow_style=None)
            command += ["--effects", stem + ".effects.yaml"]
        if run(command, log):
            with open(log) as handle:
                last = handle.read().splitlines()[-1]
                if any(text in last for text in UNFLYABLE):
                    return dict(case, unflyable=log)
            return dict(case, error="simulate flight failed (see %s)" % log)
        with open(stem + ".manifest.yaml") as handle:
            manifests.setdefault(into, []).extend(yaml.safe_load(handle)["flights"])
    for path, flights in manifests.items():
        with open(path, "w") as handle:
            yaml.safe_dump({"flights": flights}, handle, default_flow_style=None)
    if args.family:
        with open(drawn, "w") as handle:
            yaml.safe_dump(case["family"], handle, default_flow_style=None)
    if args.simulate_only:
        return dict(case, simulated=True)
    return diagnose_and_score(case, args, folder, model, manifest, log)


def diagnose_and_score(case, args, folder, model, manifest, log):
    """The case's row (score); with --compare-rpm-view also what it names without the RPM view."""
    row = score(case, diagnose(case, args, folder, model, manifest, log))
    if args.family and case["label"] in NO_REFERENCE_LABELS and "error" not in row:
        alone = diagnose(case, args, folder, model, manifest, log, reference=False)
        if isinstance(alone, str):
            return dict(row, error=alone)
        row["suspect_without_reference"] = alone["where"].get("suspect_motor")
    if args.compare_whole_flights and "error" not in row:
        whole = score(case, diagnose(case, args, folder, model, whole_manifest(manifest), log, whole=True))
        if "error" in whole:
            return dict(row, error=whole["error"])
        row.update(right_whole=whole["right"], named_whole=outcome(whole))
    if args.compare_rpm_view and "error" not in row:
        without = score(case, diagnose(case, args, folder, model, manifest, log, rpm_view=False))
        if "error" in without:
            return dict(row, error=without["error"])
        row.update(right_without_rpm_view=without["right"], named_without_rpm_view=outcome(without))
    return row


def whole_manifest(manifest):
    """The case's manifest as a user without hand-cut segments writes it: per flight its log and the
    mass of each lift (its segments' masses, a lift split by a ground contact counted once)."""
    with open(manifest) as handle:
        flights = yaml.safe_load(handle)["flights"]
    whole = []
    for flight in flights:
        masses = []
        for segment in flight["segments"]:
            if not masses or masses[-1] != segment["mass_kg"]:
                masses.append(segment["mass_kg"])
        whole.append({"log": flight.get("log", flight.get("bag")), "mass_kg": masses})
    path = os.path.join(os.path.dirname(manifest), "whole.manifest.yaml")
    with open(path, "w") as handle:
        yaml.safe_dump({"flights": whole}, handle, default_flow_style=None)
    return path


def diagnose(case, args, folder, model, manifest, log, rpm_view=True, reference=True, whole=False):
    """Runs diagnose_gap on a case's flights (without ESC telemetry's RPM view when `rpm_view` is
    False, into a folder of its own); returns its report, or an error text."""
    tool = lambda name: os.path.join(args.bin, name)  # noqa: E731
    urdf = os.path.join(args.repo, "config/f450_quad.urdf")
    out = os.path.join(folder, "diagnosis_whole" if whole else "diagnosis" if rpm_view and reference else
                       "diagnosis_no_rpm_view" if reference else "diagnosis_no_reference")
    command = [tool("diagnose_gap"), "--model", model, "--manifest", manifest, "--urdf", urdf, "--out", out,
               "--python", sys.executable] + ([] if rpm_view else ["--no-rpm-view"])
    if reference and wants_reference(case, args):
        command += ["--reference", os.path.join(folder, "reference.manifest.yaml")]
    if args.no_figures:
        # A plot script that draws nothing: the figures are most of a re-diagnosis' time.
        quiet = os.path.join(args.work, "no_figures.py")
        with open(quiet, "w") as handle:
            handle.write("# validate_gap.py --no-figures\n")
        command += ["--plot-script", quiet]
    code = run(command, log)
    report_path = os.path.join(out, "report.yaml")
    if not os.path.exists(report_path):
        return "diagnose_gap wrote no report (exit %d, see %s)" % (code, log)
    with open(report_path) as handle:
        report = yaml.safe_load(handle)
    with open(os.path.join(out, "motor_health.yaml")) as handle:
        report["motor_health"] = yaml.safe_load(handle)["flights"]
    check = os.path.join(out, "model_check.yaml")
    if os.path.exists(check):
        with open(check) as handle:
            report["model_check"] = yaml.safe_load(handle)["flights"]
    return report


def score(case, report):
    """The case's row: what was selected and suspected, the held-out figures, and whether it is right."""
    if isinstance(report, str):
        return dict(case, error=report)
    selected = sorted(report.get("selected") or [])
    ambiguous = [sorted(group) for group in report.get("ambiguous") or []]
    suspect = report["where"].get("suspect_motor")
    held = report["heldout"]
    nested = held.get("nested") or {}
    row = dict(case, selected=selected, ambiguous=ambiguous, suspect=suspect, before=held["before_rmse_pct"],
               after=held["after_rmse_pct"], nested_before=nested.get("before_rmse_pct"),
               nested_after=nested.get("after_rmse_pct"),
               payload_before=held["before_payload_err_pct"], payload_after=held["after_payload_err_pct"])
    expected = sorted(case["effects"])
    suspect_right = suspect is None
    if case.get("fault", {}).get("weak_propeller"):
        suspect_right = suspect == case["fault"]["weak_propeller"]["motor"]
    row["right"] = selected == expected and not ambiguous and suspect_right
    # An honest "one of these": nothing wrong in selected, every true effect selected or in a group,
    # and every group holding a true effect.
    in_groups = {name for group in ambiguous for name in group}
    row["ambiguous_ok"] = bool(ambiguous and suspect_right and set(selected) <= set(expected)
                               and set(expected) <= set(selected) | in_groups
                               and all(set(group) & set(expected) for group in ambiguous))
    # The onboard check (~capability) on each flight: a flag on a flight without a motor fault is
    # a false alarm; on a weak propeller's flight, the flag is on its channel or on another.
    weak = case.get("fault", {}).get("weak_propeller")
    flags = [flight["flagged"] for flight in report["motor_health"]]
    row["health_flights"] = len(flags)
    # ESCs each given their own offset differ as they did not on the reference flights (see below).
    each = case.get("esc_each")
    row["health_false"] = 0 if weak or each else sum(1 for f in flags if f)
    row["health_esc_each"] = sum(1 for f in flags if f) if each else 0
    row["health_found"] = sum(1 for f in flags if weak and weak["motor"] in f)
    row["health_elsewhere"] = sum(1 for f in flags if weak and any(c != weak["motor"] for c in f))
    # The live model check of ESC telemetry (issue 21) on each flight with telemetry: a motor
    # flagged without a weak propeller, or any verdict on a case with nothing injected, is a false
    # alarm (a supply verdict is right for an effect every motor shares, as a supply resistance).
    checks = [flight for flight in report.get("model_check") or [] if flight["telemetry"]]
    nothing = not case["effects"] and not case.get("fault")
    row["check_flights"] = len(checks)
    # ESCs each given their own offset (the messy world's law of esc_offset) differ from one another
    # as they did not on the reference flights: a motor flagged there is a change, counted apart.
    row["esc_each"] = bool(case.get("esc_each"))
    row["check_false"] = 0 if row["esc_each"] else sum(
        1 for c in checks if (not weak and c["flagged"]) or (nothing and c["verdicts"]))
    row["check_esc_each"] = sum(1 for c in checks if c["flagged"]) if row["esc_each"] else 0
    row["check_found"] = sum(1 for c in checks if weak and weak["motor"] in c["flagged"])
    return row


# Issue 33's bar: a propeller at this share of its thrust, or weaker, located on its own motor.
WEAK_BAR_THRUST = 0.92


def make_cases(count, seed, quick, effects, weak_thrust=(0.8, 0.9)):
    rng = random.Random(seed)
    missing = [name for name in effects if name not in SIMULATED]
    if missing:
        raise SystemExit("validate_gap.py: the simulator injects no %s: add it to draw_effect" % ", ".join(missing))
    kinds = ([("null", [])] + [(name, [name]) for name in effects]
             + [("two", None), ("weak_propeller", []), ("cg_offset", [])])
    if quick:
        kinds = [("null", []), ("thrust_loss", ["thrust_loss"]), ("supply_resistance", ["supply_resistance"]),
                 ("weak_propeller", [])]
        count = len(kinds)
    cases = []
    for index in range(count):
        label, names = kinds[index % len(kinds)]
        if names is None:
            names = sorted(rng.sample(["supply_resistance", "thrust_loss", "ground_effect", "esc_offset",
                                       "climb_inflow", "translational_lift"], 2))
        case = {"name": "case_%02d_%s" % (index + 1, label), "label": label, "seed": rng.randrange(1, 10**6),
                "flights": 5, "effects": {name: draw_effect(name, rng) for name in names}}
        if label == "weak_propeller":
            case["fault"] = {"weak_propeller": {"motor": rng.randint(1, 4),
                                                "thrust_factor": round(rng.uniform(*weak_thrust), 3)}}
            # Chipped (thrust and torque down) or worn (thrust down, torque kept), drawn from a
            # stream of its own (the case's seed also drives its flights' draws) so that the other
            # cases of a seed stay as they were drawn before.
            case["fault"]["weak_propeller"]["damage"] = random.Random("damage-%d" % case["seed"]).choice(
                ["chipped", "worn"])
        if label == "cg_offset":
            angle = rng.uniform(0, 6.283)
            case["fault"] = {"cg_offset_m": [round(0.01 * math.cos(angle), 4),
                                             round(0.01 * math.sin(angle), 4), 0.0]}
        cases.append(case)
    return cases


def outcome(row):
    """What a case's report named: its selected effects, and each ambiguous group as (a or b)."""
    names = list(row.get("selected") or []) + ["(%s)" % " or ".join(g) for g in row.get("ambiguous") or []]
    return " + ".join(names or ["none"])


def summarise(rows):
    lines = []
    labels = sorted({r["label"] for r in rows})
    outcomes = sorted({outcome(r) for r in rows if "error" not in r})
    lines.append("| injected \\ selected | " + " | ".join(outcomes) + " | right |")
    lines.append("|---" * (len(outcomes) + 2) + "|")
    for label in labels:
        mine = [r for r in rows if r["label"] == label and "error" not in r]
        counts = [sum(1 for r in mine if outcome(r) == o) for o in outcomes]
        lines.append("| %s | %s | %d/%d |" % (label, " | ".join(str(c) for c in counts),
                                               sum(r["right"] for r in mine), len(mine)))
    return lines


def write_section(path, marker, text):
    """Writes `text` between <!-- marker --> lines of `path`, keeping the rest of the file."""
    begin, end = "<!-- %s -->" % marker, "<!-- /%s -->" % marker
    old = open(path).read() if os.path.exists(path) else "# Validation of diagnose_gap\n"
    block = begin + "\n" + text.rstrip("\n") + "\n" + end + "\n"
    if begin in old and end in old:
        new = old[:old.index(begin)] + block + old[old.index(end) + len(end) + 1:]
    else:
        new = old.rstrip("\n") + "\n\n" + block
    with open(path, "w") as handle:
        handle.write(new)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", required=True)
    parser.add_argument("--repo", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--cases", type=int, default=44)
    parser.add_argument("--seed", type=int, help="repeat a run (default: a fresh seed, printed)")
    parser.add_argument("--family", action="store_true",
                        help="draw each case's hardware and vehicle from the randomized family (draw_family)")
    parser.add_argument("--plain-world", action="store_true",
                        help="with --family: the family as before 2026-11-28 afternoon (no background physics, the "
                             "effects' plain laws, weak propellers at 80-90 %%), to repeat the sections run on it")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--reuse", action="store_true", help="diagnose the flights already simulated in --work again")
    parser.add_argument("--no-figures", action="store_true", help="diagnose without drawing the report's figures")
    parser.add_argument("--simulate-missing", action="store_true",
                        help="with --reuse: simulate the cases whose simulation is not in --work (a failed one again)")
    parser.add_argument("--simulate-only", action="store_true",
                        help="simulate the cases and stop (diagnose them later with --reuse)")
    parser.add_argument("--compare-rpm-view", action="store_true",
                        help="diagnose each case also without ESC telemetry's RPM view (diagnose_gap --no-rpm-view) "
                             "and compare (issue 21: right on at least as many cases with it)")
    parser.add_argument("--compare-whole-flights", action="store_true",
                        help="diagnose each case also from whole-flight masses (no segments) and compare")
    parser.add_argument("--only", help="comma-separated case labels to run (null,weak_propeller,...): for calibration")
    parser.add_argument("--case", help="comma-separated numbers of the seed's cases to run (39 for case_39_...), drawn "
                                       "as in the whole run: a case a change was made for, kept as a regression test")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--markdown")
    parser.add_argument("--junit")
    args = parser.parse_args()
    if args.seed is None:
        args.seed = random.SystemRandom().randrange(1, 10**6)
    print("SEED=%d%s" % (args.seed, " (family, plain world)" if args.family and args.plain_world
                          else " (family)" if args.family else ""), flush=True)
    # The family's weak propellers around the 92 % of issue 33's target; the fixed suite's and the
    # plain world's as before.
    weak_thrust = (0.90, 0.94) if args.family and not args.plain_world else (0.8, 0.9)
    cases = make_cases(args.cases, args.seed, args.quick, known_effects(args.bin), weak_thrust)
    if args.case:
        # Numbered as in the whole run, before --only picks labels among them.
        numbers = {int(number) for number in args.case.split(",")}
        if not numbers <= set(range(1, len(cases) + 1)):
            parser.error("--case %s: the run has cases 1..%d" % (args.case, len(cases)))
        cases = [case for index, case in enumerate(cases) if index + 1 in numbers]
    if args.only:
        cases = [case for case in cases if case["label"] in args.only.split(",")]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        rows = list(pool.map(lambda case: run_case(case, args), cases))
    errors = [r for r in rows if "error" in r]
    if args.simulate_only:
        print("Simulated %d cases, %d failed%s" % (len(rows), len(errors),
                                                  "".join("\n%s: %s" % (r["name"], r["error"]) for r in errors)))
        return 0 if not errors else 1
    done = [r for r in rows if "error" not in r]
    right = sum(r["right"] for r in done)
    ambiguous_ok = [r for r in done if r["ambiguous_ok"]]
    ambiguous_bad = [r for r in done if r["ambiguous"] and not r["ambiguous_ok"]]
    injected = [r for r in done if r["effects"] and r["before"]]
    shrink = [100.0 * (1.0 - r["after"] / r["before"]) for r in injected]
    nulls = [r for r in done if r["label"] == "null"]
    floor = sum(r["before"] for r in nulls) / len(nulls) if nulls else 0.0
    excess = [100.0 * (r["before"] - r["after"]) / (r["before"] - floor) for r in injected if r["before"] > floor]
    # Nested: the flights that score took no part in selecting or fitting anything (the suspect
    # motor's factor included); its floor is the null cases' plain-model error on the same flights.
    nested = [r for r in injected if r["nested_before"] and r["nested_after"] is not None]
    nested_nulls = [r for r in nulls if r["nested_before"]]
    nested_floor = (sum(r["nested_before"] for r in nested_nulls) / len(nested_nulls)) if nested_nulls else 0.0
    nested_excess = [100.0 * (r["nested_before"] - r["nested_after"]) / (r["nested_before"] - nested_floor)
                     for r in nested if r["nested_before"] > nested_floor]
    mean_nested = sum(nested_excess) / len(nested_excess) if nested_excess else float("nan")
    wrongly_named = [r for r in done if set(r["selected"]) - set(r["effects"])]
    nulls_named = [r for r in done if not r["effects"] and r["selected"]]
    weak = [r for r in done if r["label"] == "weak_propeller"]
    weak_right = sum(r["right"] for r in weak)
    # Issue 33's bar is a propeller at 92 % of its thrust; the family also draws milder ones.
    weak_bar = [r for r in weak if r["fault"]["weak_propeller"]["thrust_factor"] <= WEAK_BAR_THRUST]
    mean_shrink = sum(shrink) / len(shrink) if shrink else float("nan")
    lines = summarise(rows)
    lines.append("")
    lines.append("Right: %d of %d cases (%.0f %%); null and fault cases with an effect named: %d; weak propellers "
                 "located: %d of %d (at most %.0f %% of their thrust: %d of %d); mean held-out RMSE shrink where an "
                 "effect was injected: %.0f %% over %d cases."
                 % (right, len(done), 100.0 * right / max(len(done), 1), len(nulls_named), weak_right, len(weak),
                    100.0 * WEAK_BAR_THRUST, sum(r["right"] for r in weak_bar), len(weak_bar), mean_shrink,
                    len(shrink)))
    unfaulted = [r for r in done if r["label"] != "weak_propeller" and not r.get("esc_each")]
    false_alarms = sum(r["health_false"] for r in unfaulted)
    mean_excess = sum(excess) / len(excess) if excess else float("nan")
    lines.append("An effect wrongly named in selected: %d of %d cases (%.0f %%). Mean held-out shrink as a share of "
                 "its excess over the null floor (%.2f %%, the null cases' mean): %.0f %% over %d cases."
                 % (len(wrongly_named), len(done), 100.0 * len(wrongly_named) / max(len(done), 1), floor,
                    mean_excess, len(excess)))
    lines.append("Onboard motor-health check (~capability): capability false alarms: %d (flights flagged of %d "
                 "without a motor fault, centre-of-gravity offsets included); weak propeller flagged on its channel "
                 "on %d of %d flights, another channel flagged on %d; with ESCs each given their own offset (a change "
                 "of each ESC, not counted above) a motor flagged on %d of %d flights."
                 % (false_alarms, sum(r["health_flights"] for r in unfaulted), sum(r["health_found"] for r in weak),
                    sum(r["health_flights"] for r in weak), sum(r["health_elsewhere"] for r in weak),
                    sum(r.get("health_esc_each", 0) for r in done),
                    sum(r["health_flights"] for r in done if r.get("esc_each"))))
    alone = [r for r in done if "suspect_without_reference" in r]
    if alone:
        healthy = [r for r in alone if r["label"] != "weak_propeller"]
        weak_alone = [r for r in alone if r["label"] == "weak_propeller"]
        lines.append("Without a reference (the same cases diagnosed without --reference): no suspect motor on %d of %d "
                     "healthy vehicles (null and centre-of-gravity cases); weak propeller on its own motor on %d of %d."
                     % (sum(1 for r in healthy if r["suspect_without_reference"] is None), len(healthy),
                        sum(1 for r in weak_alone if r["suspect_without_reference"] == r["fault"]["weak_propeller"]["motor"]),
                        len(weak_alone)))
    checked = [r for r in done if r.get("check_flights")]
    if checked:
        lines.append("Live model check of ESC telemetry (issue 21): false alarms on %d of %d flights without a weak "
                     "propeller (a motor flagged, or any verdict where nothing was injected); weak propeller flagged "
                     "on its channel on %d of %d flights; with ESCs each given their own offset (a change of each ESC, not "
                     "counted above) a motor flagged on %d of %d flights."
                     % (sum(r["check_false"] for r in checked if r["label"] != "weak_propeller"),
                        sum(r["check_flights"] for r in checked if r["label"] != "weak_propeller" and not r["esc_each"]),
                        sum(r["check_found"] for r in checked if r["label"] == "weak_propeller"),
                        sum(r["check_flights"] for r in checked if r["label"] == "weak_propeller"),
                        sum(r["check_esc_each"] for r in checked), sum(r["check_flights"] for r in checked if r["esc_each"])))
    lines.append("Ambiguous (counted apart, not right): %d of %d cases (%.0f %%) with the truth among the candidates, "
                 "%d without. Nested held-out shrink of the excess over the null floor (%.2f %%), scored on flights "
                 "that took no part in selecting or fitting: %.0f %% over %d cases (selection-time figure above)."
                 % (len(ambiguous_ok), len(done), 100.0 * len(ambiguous_ok) / max(len(done), 1), len(ambiguous_bad),
                    nested_floor, mean_nested, len(nested_excess)))
    whole_worse = False
    if args.compare_whole_flights:
        right_whole = sum(r["right_whole"] for r in done)
        alike = sum(r["named_whole"] == outcome(r) for r in done)
        differ = ["%s (%s, whole: %s)" % (r["name"], outcome(r), r["named_whole"]) for r in done
                  if r["named_whole"] != outcome(r)]
        whole_worse = right_whole < right
        lines.append("Weighed as whole flights (issue 35: each flight's mass per airborne stretch, the stretches "
                     "found in its log, no hand-cut segments): right on %d of %d cases (%d with the simulator's "
                     "spans); named alike on %d of %d; named otherwise: %s."
                     % (right_whole, len(done), right, alike, len(done), "; ".join(differ) or "none"))
    rpm_view_worse = False
    if args.compare_rpm_view:
        right_without = sum(r["right_without_rpm_view"] for r in done)
        only_with = [r["name"] for r in done if r["right"] and not r["right_without_rpm_view"]]
        only_without = ["%s (%s with it)" % (r["name"], outcome(r)) for r in done
                        if r["right_without_rpm_view"] and not r["right"]]
        rpm_view_worse = right < right_without
        lines.append("The RPM view (ESC telemetry's rotor speeds, issue 21): right on %d of %d cases with it, %d "
                     "without it (diagnose_gap --no-rpm-view); right only with it: %s; right only without it: %s."
                     % (right, len(done), right_without, ", ".join(only_with) or "none",
                        ", ".join(only_without) or "none"))
    for r in errors:
        lines.append("Error in %s: %s" % (r["name"], r["error"]))
    lines.append("")
    lines.append("| case | injected | named | suspect | held-out RMSE % before | after | nested before | nested after "
                 "| payload err % before | after |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    cell = lambda value: "n/a" if value is None else "%.2f" % value  # noqa: E731
    for r in done:
        injected_text = ", ".join("%s %s" % (k, v) for k, v in r["effects"].items()) or "none"
        if r.get("fault"):
            injected_text += " " + str(r["fault"])
        lines.append("| %s | %s | %s | %s | %.2f | %.2f | %s | %s | %s | %s |" % (
            r["name"], injected_text, outcome(r), r["suspect"], r["before"], r["after"], cell(r["nested_before"]),
            cell(r["nested_after"]), r["payload_before"], r["payload_after"]))
    print("\n".join(lines))
    if args.family:
        # Issue 18's targets on the randomized family.
        passed = (not errors and right >= 0.9 * len(done) and len(wrongly_named) <= 0.02 * len(done)
                  and not nulls_named and weak_right >= 0.9 * len(weak) and len(ambiguous_ok) <= 0.1 * len(done)
                  and not ambiguous_bad and (not nested_excess or mean_nested >= 70.0) and not rpm_view_worse
                  and not whole_worse)
    else:
        passed = (not errors and right >= 0.9 * len(done) and not nulls_named and weak_right == len(weak)
                  and (not shrink or mean_shrink >= 70.0) and false_alarms == 0 and not whole_worse)
    machine = "%s %s, %d cores" % (platform.system(), platform.machine(), os.cpu_count() or 1)
    today = datetime.date.today().isoformat()
    if args.markdown and args.family:
        write_section(args.markdown, "validate_gap:family seed %d" % args.seed,
                      "## Randomized family, seed %d (%s)\n\n"
                      "Run on %s with `make validate-gap SEED=%d` (`scripts/validate_gap.py --family --cases %d "
                      "--seed %d`) on %s. Each case draws its hardware and vehicle from the family (ESC end points "
                      "and bridge resistance, motor Kv, winding resistance, no-load current, flux and thermal "
                      "coefficients, propeller thrust and torque coefficients independently, battery resistances, "
                      "drag, centre of gravity, the avionics' own 0.2-2 A on the battery current; each motor's own "
                      "parts: propeller thrust and torque coefficients 1-4 %%, Kv 1-2 %%, ESC end points 3-10 us "
                      "apart from motor to motor, one spin direction's propellers turning 0-8 %% more torque per "
                      "thrust), its bench sweep is simulated with that hardware and fitted, and its five flights "
                      "are flown with it, each hanging its payload within 4 mm (x, y) of the attach point%s; every "
                      "case is diagnosed against three more healthy flights of the same vehicle as built "
                      "(diagnose_gap --reference; the case's effect and weak propeller left out, its centre of "
                      "gravity kept), the null, centre-of-gravity and weak-propeller cases also without them. Targets (issue 18): >= 90 %% exactly right, <= 2 %% with an effect wrongly named, "
                      "<= 10 %% ambiguous (the truth among the candidates; counted apart, not right), no null or "
                      "fault case named, >= 90 %% of weak propellers on their own motor, >= 70 %% mean nested "
                      "held-out shrink of the excess over the null floor (flights that took no part in selecting "
                      "or fitting). %s\n\n"
                      % (args.seed, "passed" if passed else "targets missed", today, args.seed, args.cases,
                         args.seed, machine, WORLD_PLAIN if args.plain_world else WORLD_MESSY,
                         "PASSED." if passed else "Targets missed.")
                      + "\n".join(lines) + "\n")
    elif args.markdown:
        write_section(args.markdown, "validate_gap:fixed",
                      "## The fixed suite (seed %d, the thesis hardware)\n\n" % args.seed +
                      "Run on %s with `make validate-gap-fixed` (`scripts/validate_gap.py --cases %d --seed %d`) on %s. "
                      "Each case: a clean bench sweep simulated and fitted with fit_surfaces, five flights "
                      "simulated with the injected effect or fault, diagnose_gap told nothing of it. Right means "
                      "exactly the injected effects selected (none for null, weak-propeller and "
                      "centre-of-gravity cases) and, for a weak propeller, its motor the suspect. Targets (issue "
                      "8): >= 90 %% right, no null or fault case named, every weak propeller located, >= 70 %% "
                      "mean held-out RMSE shrink where an effect was injected; and (issue 10) no capability false alarm: the "
                      "onboard motor-health check, replayed on every flight, flags nothing without a motor fault. "
                      "This suite was re-run while the diagnosis was tuned: it measures the fit to our simulator, "
                      "not a validation (the randomized family's sections are).\n\n"
                      % (today, args.cases, args.seed, machine) + "\n".join(lines) + "\n")
    if args.junit:
        os.makedirs(os.path.dirname(os.path.abspath(args.junit)), exist_ok=True)
        with open(args.junit, "w") as handle:
            failure = "" if passed else '<failure message="acceptance thresholds missed"/>'
            handle.write('<?xml version="1.0"?>\n<testsuite name="validate_gap" tests="1" errors="0" failures="%d">'
                         '<testcase classname="validate_gap" name="cases">%s</testcase></testsuite>\n'
                         % (0 if passed else 1, failure))
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
