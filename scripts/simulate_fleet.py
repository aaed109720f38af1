#!/usr/bin/env python3
"""Simulates a fleet for `fleet` (docs/fleet.md): vehicles of one type, each with its own parts
(validate_gap.draw_family's spread: propeller coefficients, Kv and ESC end points from motor to
motor, one spin direction's propellers unlike the other's, drag, centre of gravity, avionics),
two packs each with their own resistance, flights of random payloads hung a few millimetres off
centre in the day's air with background physics on; three healthy reference flights per vehicle;
and the scenario's events (SCENARIO): one rotor whose propeller wears flight by flight, one
vehicle whose propeller is swapped for another make halfway, one pack that ages. The fleet's
bench model comes from a bench sweep of the type fitted with fit_surfaces, as an operator's would.

Usage: simulate_fleet.py --bin DIR --repo DIR --out DIR [--vehicles 20] [--flights 30] [--seed 2027]
                         [--jobs 2] [--format ulog|bag|dataflash]
Writes DIR/fleet.yaml (the description), DIR/model.yaml, DIR/node_params.yaml, DIR/<vehicle>/
reference.manifest.yaml with its flights, and DIR/logs/<vehicle>_flight_<nnn>_pack-<P>.<ext>."""
import argparse
import concurrent.futures
import math
import os
import random
import shutil
import subprocess
import sys

import yaml

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import validate_gap  # noqa: E402  (the family's draws and background physics)

# What happens in the fleet (1-based flights and motors). The wear starts after a few healthy
# flights and loses `rate` of the propeller's thrust per flight: at 30 flights it is well past the
# 5 % band, at 20 still inside it.
SCENARIO = {
    "worn": {"vehicle": 7, "motor": 3, "onset_flight": 8, "rate": 0.0035},
    "swap": {"vehicle": 13, "motor": 2, "from_flight": 16, "thrust_factor": 0.96},
    "ageing_pack": {"vehicle": 4, "pack": "B", "growth": 0.8},  # its resistance x (1 + growth) over its flights
}
EXTENSIONS = {"ulog": "ulg", "bag": "bag", "dataflash": "bin"}


def vehicle_name(index):
    return "v%02d" % index


def worn_factor(flight):
    worn = SCENARIO["worn"]
    return 1.0 - worn["rate"] * max(0, flight - worn["onset_flight"])


def profile_for(rng, urdf, vehicle, fault):
    """A short flight: a payload of 0-0.2 kg hung off centre, take-off, hover, climb, hover,
    descent, hover, landing (about 70 s)."""
    payload = round(rng.uniform(0.02, 0.2), 3)
    segments = [{"type": "wait", "duration_s": 3}]
    if payload > 0:
        segments.append({"type": "payload", "mass_kg": payload, "duration_s": 3})
    low = round(rng.uniform(1.8, 2.5), 2)
    segments += [{"type": "takeoff", "height_m": low, "rate_m_s": 1.0},
                 {"type": "hover", "duration_s": round(rng.uniform(22, 28))},
                 {"type": "climb", "height_m": round(rng.uniform(5.0, 7.0), 2), "rate_m_s": round(rng.uniform(0.8, 1.5), 2)},
                 {"type": "hover", "duration_s": round(rng.uniform(10, 14))},
                 {"type": "descend", "height_m": low, "rate_m_s": round(rng.uniform(0.8, 1.2), 2)},
                 {"type": "hover", "duration_s": round(rng.uniform(10, 14))},
                 {"type": "land", "rate_m_s": 0.6}, {"type": "wait", "duration_s": 2}]
    point = [round(rng.uniform(-0.004, 0.004), 4), round(rng.uniform(-0.004, 0.004), 4), -0.04]
    profile = {
        "autopilot": {"flavour": "px4", "pwm_min_us": 1100, "pwm_max_us": 1950, "disarmed_pwm_us": 900,
                      "rc_out_rate_hz": 20},
        "vehicle": dict({"urdf": urdf, "landing_gear": {"height_m": 0.12, "half_width_m": 0.12},
                         "battery_initial_soc": round(rng.uniform(0.85, 1.0), 2)}, **vehicle),
        "payload_cable": {"length_m": 0.15, "attach_point_m": point, "stiffness_n_per_m": 1000,
                          "damping_n_s_per_m": 10},
        "manifest": {"settle_s": 4, "spans": "airborne"},
        "segments": segments,
    }
    if fault:
        profile["faults"] = {"weak_propeller": fault}
    return profile


def plan(args):
    """Every flight to simulate: (vehicle, stem, params, profile, effects, seed, manifest wanted)."""
    type_hardware, _ = validate_gap.draw_family(args.seed)
    flights = []
    packs = {}
    for index in range(1, args.vehicles + 1):
        name = vehicle_name(index)
        _, vehicle = validate_gap.draw_family(args.seed * 1000 + index)
        rng = random.Random("fleet-%d-%s" % (args.seed, name))
        for pack in ("A", "B"):
            packs[(name, pack)] = round(type_hardware["battery"]["series_resistance_ohm"] * rng.uniform(0.8, 1.25), 5)
        runs = [("reference_%d" % i, None, "A" if i % 2 else "B", True) for i in range(1, 4)]
        runs += [("flight_%03d" % f, f, "AB"[(f - 1) % 2], False) for f in range(1, args.flights + 1)]
        pack_flights = {"A": 0, "B": 0}
        for run_name, flight, pack, reference in runs:
            flight_rng = random.Random("fleet-%d-%s-%s" % (args.seed, name, run_name))
            fault = None
            if flight and index == SCENARIO["worn"]["vehicle"] and worn_factor(flight) < 1.0:
                fault = {"motor": SCENARIO["worn"]["motor"], "thrust_factor": round(worn_factor(flight), 4),
                         "damage": "worn"}
            swap = SCENARIO["swap"]
            if flight and index == swap["vehicle"] and flight >= swap["from_flight"]:
                fault = {"motor": swap["motor"], "thrust_factor": swap["thrust_factor"], "damage": "chipped"}
            resistance = packs[(name, pack)]
            ageing = SCENARIO["ageing_pack"]
            if flight and index == ageing["vehicle"] and pack == ageing["pack"]:
                pack_flights[pack] += 1
                resistance *= 1.0 + ageing["growth"] * (pack_flights[pack] - 1) / max(1, args.flights // 2 - 1)
            hardware = dict(type_hardware, battery=dict(type_hardware["battery"], series_resistance_ohm=round(resistance, 5)))
            effects = validate_gap.background_effects(args.seed * 1000 + index, run_name, hardware)
            stem = (os.path.join(args.out, name, run_name) if reference else
                    os.path.join(args.out, "logs", "%s_%s_pack-%s%s" % (name, run_name, name, pack)))
            flights.append(dict(vehicle=name, stem=stem, hardware=hardware, profile=profile_for(
                flight_rng, args.urdf, vehicle, fault), effects=effects, seed=args.seed * 100000 + index * 100 + (
                    flight or 90 + int(run_name[-1])), reference=reference))
    return type_hardware, flights


def simulate(flight, args):
    """One flight simulated; returns its manifest entries (reference flights) or []."""
    stem = flight["stem"]
    os.makedirs(os.path.dirname(stem), exist_ok=True)
    for suffix, content in (("params", None), ("profile", flight["profile"]), ("effects", flight["effects"])):
        if content is not None:
            with open("%s.%s.yaml" % (stem, suffix), "w") as handle:
                yaml.safe_dump(content, handle, default_flow_style=None)
    validate_gap.family_params(os.path.join(args.repo, "config/sim/e300_dji2212_dji9443.yaml"), flight["hardware"],
                               stem + ".params.yaml")
    log = "%s.%s" % (stem, EXTENSIONS[args.format])
    command = [os.path.join(args.bin, "simulate"), "flight", "--params", stem + ".params.yaml", "--profile",
               stem + ".profile.yaml", "--effects", stem + ".effects.yaml", "--seed", str(flight["seed"]), "--log", log,
               "--log-format", args.format]
    if flight["reference"]:
        command += ["--manifest", stem + ".manifest.yaml"]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(command), done.stdout.strip().splitlines()[-1]))
    for suffix in ("params", "profile", "effects"):
        if not flight["reference"]:
            os.remove("%s.%s.yaml" % (stem, suffix))
    if not flight["reference"]:
        return []
    with open(stem + ".manifest.yaml") as handle:
        entries = yaml.safe_load(handle)["flights"]
    for entry in entries:
        entry["log"] = os.path.basename(entry["log"])
    return entries


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", required=True)
    parser.add_argument("--repo", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--vehicles", type=int, default=20)
    parser.add_argument("--flights", type=int, default=30)
    parser.add_argument("--seed", type=int, default=2027)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--format", choices=sorted(EXTENSIONS), default="ulog")
    args = parser.parse_args()
    args.out = os.path.abspath(args.out)  # the profiles name the URDF from their own folders
    if os.path.exists(args.out):
        shutil.rmtree(args.out)
    os.makedirs(args.out)
    args.urdf = os.path.join(args.out, "f450_quad.urdf")
    shutil.copy(os.path.join(args.repo, "config/f450_quad.urdf"), args.urdf)
    type_hardware, flights = plan(args)
    params = os.path.join(args.out, "type.params.yaml")
    validate_gap.family_params(os.path.join(args.repo, "config/sim/e300_dji2212_dji9443.yaml"), type_hardware, params)
    for command in ([os.path.join(args.bin, "simulate"), "bench", "--params", params, "--experiment", "pwm_sweep",
                     "--seed", str(args.seed), "--output", os.path.join(args.out, "bench.csv")],
                    [os.path.join(args.bin, "fit_surfaces"), os.path.join(args.out, "bench.csv"), "--out",
                     os.path.join(args.out, "model.yaml")]):
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        entries = list(pool.map(lambda flight: (flight["vehicle"], simulate(flight, args)), flights))
    manifests = {}
    for name, flown in entries:
        manifests.setdefault(name, []).extend(flown)
    vehicles = []
    for name in sorted(manifests):
        with open(os.path.join(args.out, name, "reference.manifest.yaml"), "w") as handle:
            yaml.safe_dump({"flights": manifests[name]}, handle, default_flow_style=None)
        vehicles.append({"name": name, "model": "model.yaml", "urdf": "f450_quad.urdf",
                         "reference": "%s/reference.manifest.yaml" % name, "params": "node_params.yaml"})
    with open(os.path.join(args.out, "node_params.yaml"), "w") as handle:
        yaml.safe_dump({"capability": {"battery": {"cells": 3, "capacity_ah": 4.0}}}, handle)
    with open(os.path.join(args.out, "fleet.yaml"), "w") as handle:
        handle.write("# A simulated fleet (scripts/simulate_fleet.py, seed %d): %d vehicles, %d flights each.\n" %
                     (args.seed, args.vehicles, args.flights))
        yaml.safe_dump({"vehicles": vehicles, "logs": ["logs/*.%s" % EXTENSIONS[args.format]],
                        "vehicle_pattern": "^(?P<vehicle>v[0-9]+)_", "pack_pattern": "pack-(?P<pack>[A-Za-z0-9]+)"},
                       handle, default_flow_style=False, sort_keys=False)
    print("simulate_fleet: %d vehicles, %d flights each -> %s/fleet.yaml" % (args.vehicles, args.flights, args.out))


if __name__ == "__main__":
    main()
