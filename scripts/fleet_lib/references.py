"""Each vehicle's healthy reference: its model's `motor_reference` (a corrected_model.yaml that
`diagnose_gap --reference` wrote), or learned once from the description's `reference:` manifest by
`diagnose_gap` and kept beside the database, keyed by the content of the model, URDF and manifest,
so that a changed reference is learned again and an unchanged one never."""
import hashlib
import os
import shutil
import subprocess

import yaml


class ReferenceError(Exception):
    """A reference that cannot be learned or read, one line naming the vehicle."""


def motor_count(model_path):
    """The rotors of the model's motor_reference, or None when it carries none."""
    with open(model_path) as handle:
        model = yaml.safe_load(handle)
    reference = model.get("motor_reference") if isinstance(model, dict) else None
    if not isinstance(reference, dict) or "shares" not in reference:
        return None
    return len(reference["shares"])


def _digest(paths):
    digest = hashlib.sha256()
    for path in paths:
        with open(path, "rb") as handle:
            digest.update(handle.read())
    return digest.hexdigest()[:16]


def model_for(vehicle, folder, diagnose_gap, python):
    """The model the vehicle's flights are estimated with: its own model when no reference manifest
    is given, else the corrected model diagnose_gap learned from the manifest's healthy flights
    (learned now unless kept from an earlier run in `folder`)."""
    if vehicle.reference is None:
        return vehicle.model
    key = _digest([vehicle.model, vehicle.urdf, vehicle.reference])
    out = os.path.join(folder, "references", "%s-%s" % (vehicle.name, key))
    model = os.path.join(out, "corrected_model.yaml")
    if os.path.exists(model):
        return model
    partial = "%s.partial-%d" % (out, os.getpid())
    os.makedirs(partial, exist_ok=True)
    done = subprocess.run([diagnose_gap, "--model", vehicle.model, "--urdf", vehicle.urdf, "--manifest",
                           vehicle.reference, "--reference", vehicle.reference, "--out", partial,
                           "--python", python],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    learned = os.path.join(partial, "corrected_model.yaml")
    if done.returncode != 0 or not os.path.exists(learned) or motor_count(learned) is None:
        lines = [line for line in done.stdout.splitlines() if line.strip()]
        raise ReferenceError("vehicle %s: its reference %s could not be learned: %s" %
                             (vehicle.name, vehicle.reference, lines[-1] if lines else "diagnose_gap said nothing"))
    if os.path.exists(out):  # learned meanwhile by another run
        shutil.rmtree(partial)
        return model
    os.replace(partial, out)  # whole or not at all: a run killed here learns it again
    return model
