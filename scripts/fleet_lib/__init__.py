"""fleet: every flight of every vehicle of a fleet estimated and judged against its own healthy
reference, kept in an SQLite database, with trends per rotor and per pack (docs/fleet.md)."""
