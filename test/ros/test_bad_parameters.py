#!/usr/bin/env python3
"""rostest: estimator_node refuses a bad configuration at start-up with one line naming the
parameter or file, and exits with status 1 (no crash, no silent default)."""
import os
import re
import shutil
import subprocess
import tempfile
import unittest

import roslib.packages
import rospkg
import rospy
import rostest

MODEL = os.path.join(rospkg.RosPack().get_path("propulsion_estimator"), "config", "e300_dji2212_dji9443.yaml")
NODE = roslib.packages.find_node("propulsion_estimator", "estimator_node")[0]


def start(name, parameters):
    """Runs the node with private parameters; returns (exit status, its FATAL line)."""
    for key in list(rospy.get_param_names()):
        if key.startswith("/" + name + "/"):
            rospy.delete_param(key)
    for key, value in parameters.items():
        rospy.set_param("/" + name + "/" + key, value)
    run = subprocess.run([NODE, "__name:=" + name], capture_output=True, text=True, timeout=60)
    text = re.sub(r"\x1b\[[0-9;]*m", "", run.stdout + run.stderr)  # rosconsole's colours
    fatal = [line for line in text.splitlines() if "[FATAL]" in line]
    return run.returncode, fatal[0].split("]: ", 1)[1] if fatal else ""


class BadParametersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_bad_parameters")

    def test_missing_model(self):
        self.assertEqual(start("a", {}), (1, "/a/model: required parameter is not set"))

    def test_model_file_missing(self):
        self.assertEqual(start("b", {"model": "/nonexistent.yaml"}), (1, "/b/model: /nonexistent.yaml: cannot open file"))

    def test_urdf_file_missing(self):
        self.assertEqual(start("u", {"model": MODEL, "urdf_file": "/nonexistent.urdf"}),
                         (1, "/u/urdf_file: /nonexistent.urdf: cannot open file"))

    def test_wrong_type(self):
        self.assertEqual(start("c", {"model": MODEL, "battery_timeout_s": "five"}),
                         (1, "/c/battery_timeout_s: wrong type, expected a number"))

    def test_misspelt_parameter(self):
        self.assertEqual(start("d", {"model": MODEL, "hover/window": 3.0}),
                         (1, "/d/hover/window: unknown parameter (see the README's parameter table)"))

    def test_invalid_value(self):
        self.assertEqual(start("e", {"model": MODEL, "hover/window_s": -1.0}),
                         (1, "hover/window_s: must be a positive number, got -1"))

    def test_diagnostic_period_not_positive(self):
        self.assertEqual(start("p", {"model": MODEL, "diagnostic_period": 0.0}),
                         (1, "/p/diagnostic_period: must be a positive number of seconds, got 0"))

    def test_battery_capacity_not_positive(self):
        self.assertEqual(start("k", {"model": MODEL, "capability/battery/capacity_ah": 0.0,
                                     "capability/battery/cells": 3}),
                         (1, "capability/battery/capacity_ah: must be a positive number, got 0"))

    def test_cutoff_above_full(self):
        self.assertEqual(start("l", {"model": MODEL, "capability/battery/capacity_ah": 4.0,
                                     "capability/battery/cells": 3, "capability/battery/cell_cutoff_v": 4.3}),
                         (1, "capability/battery/cell_cutoff_v: 4.3 V is not below the open-circuit curve's full "
                             "4.2 V"))

    def test_usable_fraction_removed(self):
        code, line = start("l", {"model": MODEL, "capability/battery/capacity_ah": 4.0,
                                 "capability/battery/cells": 3, "capability/battery/usable_fraction": 0.8})
        self.assertEqual(code, 1)
        self.assertTrue(line.startswith("/l/capability/battery/usable_fraction: removed: the usable charge follows "
                                        "from the open-circuit curve"), line)

    def test_pack_file_without_a_battery(self):
        self.assertEqual(start("m", {"model": MODEL, "capability/battery/pack_file": "/tmp/pe_pack_{pack_id}.yaml"}),
                         (1, "/m/capability/battery/pack_file: needs the pack it learns, capability/battery/capacity_ah "
                             "and cells"))

    def test_unknown_percentage_mode(self):
        self.assertEqual(start("l", {"model": MODEL, "capability/battery/percentage": "remaining"}),
                         (1, "capability/battery/percentage: \"remaining\" is not ignore, px4_remaining or "
                             "capacity_fraction"))

    def test_window_fill_never_met(self):
        self.assertEqual(start("i", {"model": MODEL, "hover/min_window_fill": 1.0}),
                         (1, "hover/min_window_fill: 1 is never reliably met: the window keeps its samples in 64 bins "
                             "and spans at least 0.9844 of hover/window_s"))

    def test_negative_publish_rate(self):
        self.assertEqual(start("j", {"model": MODEL, "publish_rate_hz": -5.0}),
                         (1, "/j/publish_rate_hz: must be 0 (every message) or a positive rate in Hz, got -5"))

    def test_channels_that_do_not_fit_the_urdf(self):
        urdf = os.path.join(os.path.dirname(MODEL), "f450_quad.urdf")
        self.assertEqual(start("f", {"model": MODEL, "urdf_file": urdf, "motor_channels": [1, 2, 3, 4, 5, 6]}),
                         (1, "motor_channels: 6 channels for a vehicle with 4 rotors"))

    def test_topic_of_an_effect_disabled(self):
        folder = tempfile.mkdtemp(prefix="pe_effects_")
        self.addCleanup(shutil.rmtree, folder, True)
        model = os.path.join(folder, "ground_effect.yaml")
        with open(MODEL) as f:
            text = f.read()
        with open(model, "w") as f:
            f.write(text + "\neffects:\n  ground_effect: {coefficient_m2: 0.0011, rotor_height_m: 0.05}\n")
        self.assertEqual(start("g", {"model": model, "rangefinder_topic": ""}),
                         (1, "/g/rangefinder_topic: empty, but the model's ground_effect effect (%s) reads it" % model))

    def test_effect_outside_its_range(self):
        folder = tempfile.mkdtemp(prefix="pe_effects_")
        self.addCleanup(shutil.rmtree, folder, True)
        model = os.path.join(folder, "thrust_loss.yaml")
        with open(MODEL) as f:
            text = f.read()
        with open(model, "w") as f:
            f.write(text + "effects:\n  thrust_loss: {fraction: 4}\n")
        line = text.count("\n") + 2  # the model's lines, then effects:, then thrust_loss
        self.assertEqual(start("h", {"model": model}),
                         (1, "/h/model: %s:%d: effects.thrust_loss.fraction: 4 is outside -0.1..0.4" % (model, line)))


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "bad_parameters", BadParametersTest)
