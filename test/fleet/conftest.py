"""fleet's tests: the package's tools from PE_BIN (the devel space's lib folder; the default is
the colcon build's), the repository from PE_REPO (default: this checkout)."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.environ.get("PE_REPO", os.path.dirname(os.path.dirname(HERE)))
BIN = os.environ.get("PE_BIN", os.path.join(REPO, ".ws/build/propulsion_estimator/devel/lib/propulsion_estimator"))
sys.path.insert(0, os.path.join(REPO, "scripts"))

import shutil  # noqa: E402
import subprocess  # noqa: E402
import tempfile  # noqa: E402

import pytest  # noqa: E402
import yaml  # noqa: E402


def simulate_fleet(out, vehicles, flights, seed):
    """A fleet simulated by scripts/simulate_fleet.py (its SCENARIO's events where its vehicles are)."""
    subprocess.run([sys.executable, os.path.join(REPO, "scripts/simulate_fleet.py"), "--bin", BIN, "--repo", REPO,
                    "--out", out, "--vehicles", str(vehicles), "--flights", str(flights), "--seed", str(seed),
                    "--jobs", "2"], check=True, stdout=subprocess.DEVNULL)


def fleet_command(description, *options):
    """The fleet tool's command line on `description`, with the package's tools."""
    return [sys.executable, os.path.join(REPO, "scripts/fleet.py"), description, "--estimate",
            os.path.join(BIN, "estimate"), "--diagnose-gap", os.path.join(BIN, "diagnose_gap")] + list(options)


def variant(folder, name, **changes):
    """A copy of folder/fleet.yaml as folder/<name>.yaml with `changes` to its keys."""
    with open(os.path.join(folder, "fleet.yaml")) as handle:
        text = yaml.safe_load(handle)
    text.update(changes)
    path = os.path.join(folder, name + ".yaml")
    with open(path, "w") as handle:
        yaml.safe_dump(text, handle, sort_keys=False)
    return path


@pytest.fixture(scope="session")
def small_fleet():
    """3 vehicles of 6 flights each (no scenario event among them), simulated once."""
    folder = tempfile.mkdtemp(prefix="fleet-small-")
    try:
        simulate_fleet(folder, 3, 6, 31)
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)
