#!/usr/bin/env python3
"""fleet: every flight of every vehicle of a fleet judged against its own healthy reference, kept in
SQLite, trends per rotor and per pack reported (docs/fleet.md)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from fleet_lib.run import main  # noqa: E402

sys.exit(main())
