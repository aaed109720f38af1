"""The fleet database (SQLite): one row per flight in `flights`, its hovers and its rotors' factors
in `hovers` and `rotors`. Schema versions are SQL migrations applied in order, the version kept in
PRAGMA user_version; each flight is written in one transaction, so that a run killed at any point
keeps every flight it finished and none half-written (docs/fleet.md#the-database)."""
import json
import sqlite3

MIGRATIONS = [
    # 1: the first schema.
    """
    CREATE TABLE runs (
      id INTEGER PRIMARY KEY,
      started_at TEXT NOT NULL,          -- UTC, ISO 8601
      description TEXT NOT NULL,         -- the fleet description's path
      engine TEXT NOT NULL               -- 'jobs N' or 'dask ADDRESS'
    );
    CREATE TABLE flights (
      id INTEGER PRIMARY KEY,
      vehicle TEXT NOT NULL,             -- as the description names it ('' when no vehicle was found)
      log TEXT NOT NULL,                 -- the log's path as found
      log_sha256 TEXT NOT NULL,          -- its content: a log seen before under another name is not run again
      log_time_utc TEXT,                 -- the log file's modification time (ISO 8601): when it was closed, where copies keep it
      pack TEXT,                         -- the pack's identity, NULL when the description gives none
      -- estimated; damaged: estimated up to where the log is damaged; refused: not estimated
      status TEXT NOT NULL CHECK (status IN ('estimated', 'damaged', 'refused')),
      problem TEXT,                      -- one line when damaged or refused
      reference TEXT NOT NULL,           -- 'vehicle' (judged against its healthy reference) or 'none'
      duration_s REAL,                   -- the log's first message to its last
      hover_mass_kg REAL,                -- the mean of the hovers' averaged total masses
      pack_resistance_ohm REAL,
      pack_resistance_std_ohm REAL,
      supply_resistance_ohm REAL,
      esc_verdict TEXT,
      flagged_channel INTEGER,           -- the motor-health check's, 0: none
      warnings TEXT NOT NULL,            -- JSON list of lines
      run_id INTEGER NOT NULL REFERENCES runs(id),
      UNIQUE (vehicle, log_sha256)
    );
    CREATE TABLE hovers (
      flight_id INTEGER NOT NULL REFERENCES flights(id),
      number INTEGER NOT NULL,           -- 1.. in time order
      start_s REAL NOT NULL, end_s REAL NOT NULL,
      total_mass_kg REAL, payload_kg REAL,
      PRIMARY KEY (flight_id, number)
    );
    CREATE TABLE rotors (
      flight_id INTEGER NOT NULL REFERENCES flights(id),
      channel INTEGER NOT NULL,
      factor REAL NOT NULL,              -- the rotor's thrust over its reference share (1: as on the healthy flights)
      factor_std REAL NOT NULL,          -- one standard deviation
      factor_low REAL NOT NULL,          -- the 90 % interval
      factor_high REAL NOT NULL,
      PRIMARY KEY (flight_id, channel)
    );
    """,
]
VERSION = len(MIGRATIONS)

# Row fields compared across engines and runs (the ids and the run differ, nothing else may).
FLIGHT_FIELDS = ("vehicle", "log", "log_sha256", "log_time_utc", "pack", "status", "problem", "reference", "duration_s", "hover_mass_kg",
                 "pack_resistance_ohm", "pack_resistance_std_ohm", "supply_resistance_ohm", "esc_verdict",
                 "flagged_channel", "warnings")


class DatabaseError(Exception):
    """A database this build cannot use, one line."""


def _statements(script):
    """The statements of an SQL script, whole (sqlite3.complete_statement: a ';' in a comment or a
    string does not end one)."""
    statements, buffer = [], ""
    for line in script.splitlines(keepends=True):
        buffer += line
        if sqlite3.complete_statement(buffer):
            statements.append(buffer)
            buffer = ""
    return statements


def connect(path):
    """The database at `path`, created or migrated to VERSION. DatabaseError for one written by a
    newer build or not a database."""
    connection = sqlite3.connect(path, isolation_level=None, timeout=60)
    try:
        connection.execute("PRAGMA journal_mode=WAL")
        connection.execute("PRAGMA foreign_keys=ON")
        version = connection.execute("PRAGMA user_version").fetchone()[0]
    except sqlite3.DatabaseError as error:
        connection.close()
        raise DatabaseError("%s: not an SQLite database (%s)" % (path, error))
    if version > VERSION:
        connection.close()
        raise DatabaseError("%s: schema version %d is newer than this build's %d" % (path, version, VERSION))
    for number in range(version, VERSION):
        connection.execute("BEGIN IMMEDIATE")
        try:
            for statement in _statements(MIGRATIONS[number]):
                connection.execute(statement)
            connection.execute("PRAGMA user_version = %d" % (number + 1))
            connection.execute("COMMIT")
        except Exception:
            connection.execute("ROLLBACK")
            raise
    return connection


def start_run(connection, started_at, description, engine):
    """A new run's id."""
    cursor = connection.execute("INSERT INTO runs (started_at, description, engine) VALUES (?, ?, ?)",
                                (started_at, description, engine))
    return cursor.lastrowid


def seen(connection):
    """The (vehicle, log_sha256) of every flight kept as estimated or damaged. A refused log is
    tried again on every run (its vehicle may have been added, its reference mended)."""
    return set(connection.execute("SELECT vehicle, log_sha256 FROM flights WHERE status != 'refused'"))


def _forget(connection, where, values):
    ids = [row[0] for row in connection.execute("SELECT id FROM flights WHERE " + where, values)]
    for flight_id in ids:
        for table in ("hovers", "rotors"):
            connection.execute("DELETE FROM %s WHERE flight_id = ?" % table, (flight_id,))
        connection.execute("DELETE FROM flights WHERE id = ?", (flight_id,))


def insert_flight(connection, row, run_id):
    """Writes one flight (a task's row) in one transaction: all of it or nothing. It replaces an
    earlier refused row of the same log and content, and an earlier refused or damaged row of the
    same log path (a log read while it was still being copied, then whole). A flight already kept
    (same vehicle and content, estimated or damaged) is left as it is; returns whether it was written."""
    connection.execute("BEGIN IMMEDIATE")
    try:
        _forget(connection, "vehicle = ? AND log_sha256 = ? AND status = 'refused'", (row["vehicle"], row["log_sha256"]))
        _forget(connection, "vehicle = ? AND log = ? AND status != 'estimated' AND log_sha256 != ?",
                (row["vehicle"], row["log"], row["log_sha256"]))
        values = [row[field] if field != "warnings" else json.dumps(row["warnings"]) for field in FLIGHT_FIELDS]
        cursor = connection.execute(
            "INSERT OR IGNORE INTO flights (%s, run_id) VALUES (%s)" % (", ".join(FLIGHT_FIELDS),
                                                                       ", ".join("?" * (len(FLIGHT_FIELDS) + 1))),
            values + [run_id])
        if cursor.rowcount == 0:
            connection.execute("ROLLBACK")
            return False
        flight_id = cursor.lastrowid
        for number, hover in enumerate(row["hovers"], start=1):
            connection.execute("INSERT INTO hovers VALUES (?, ?, ?, ?, ?, ?)",
                               (flight_id, number, hover["start_s"], hover["end_s"], hover.get("total_mass_kg"),
                                hover.get("payload_kg")))
        for rotor in row["rotors"]:
            connection.execute("INSERT INTO rotors VALUES (?, ?, ?, ?, ?, ?)",
                               (flight_id, rotor["channel"], rotor["factor"], rotor["factor_std"],
                                rotor["factor_low"], rotor["factor_high"]))
        connection.execute("COMMIT")
        return True
    except Exception:
        connection.execute("ROLLBACK")
        raise


def flights(connection):
    """Every flight as a dict (FLIGHT_FIELDS, `id`, `hovers` and `rotors` lists), warnings decoded."""
    out = []
    for values in connection.execute("SELECT id, %s FROM flights" % ", ".join(FLIGHT_FIELDS)):
        row = dict(zip(("id",) + FLIGHT_FIELDS, values))
        row["warnings"] = json.loads(row["warnings"])
        out.append(row)
    by_id = {row["id"]: row for row in out}
    for row in out:
        row["hovers"], row["rotors"] = [], []
    for flight_id, number, start, end, mass, payload in connection.execute(
            "SELECT * FROM hovers ORDER BY flight_id, number"):
        by_id[flight_id]["hovers"].append({"start_s": start, "end_s": end, "total_mass_kg": mass, "payload_kg": payload})
    for flight_id, channel, factor, std, low, high in connection.execute(
            "SELECT * FROM rotors ORDER BY flight_id, channel"):
        by_id[flight_id]["rotors"].append({"channel": channel, "factor": factor, "factor_std": std,
                                           "factor_low": low, "factor_high": high})
    return out
