"""What the fleet's database says, vehicle by vehicle: each rotor's factor over its flights judged
(trends.judge) against the healthy band, each pack's resistance (trends.pack_ageing), and the
findings a person acts on, each with its evidence in one line."""
import os

from . import description, trends


def ordered(flights):
    """Flights in flight order: a vehicle's logs by their names' natural order (PX4's and
    ArduPilot's names count up; so do the simulator's)."""
    return sorted(flights, key=lambda f: (f["vehicle"], description.natural_key(os.path.basename(f["log"])), f["log"]))


class Finding:
    """One thing to inspect or know: its vehicle, what (motor k, pack P, a log), its kind ('wear',
    'drift', 'outside', 'step', 'pack_ageing', 'refused', 'damaged') and the line that says why."""

    def __init__(self, vehicle, subject, kind, line, attention=True):
        self.vehicle, self.subject, self.kind, self.line, self.attention = vehicle, subject, kind, line, attention


def rotor_line(vehicle, channel, story, flights, band):
    """The finding of one rotor's story, or None when there is nothing to say. `flights`: the
    series' flights, each with its `number` among its vehicle's flights (1-based, log order)."""
    def flight(index):
        return "flight %d (%s)" % (flights[index]["number"], os.path.basename(flights[index]["log"]))

    where = "vehicle %s motor %d" % (vehicle, channel)
    if story["story"] == "drift" and story["rate"] < 0:
        text = ("%s is wearing: its thrust falls %.2f %% per flight (+-%.2f %%) after %s, now %.1f %% of its "
                "reference" % (where, -100 * story["rate"], 100 * story["rate_std"], flight(story["onset"]),
                               100 * story["now"]))
        if story["outside"]:
            text += ", outside the healthy band (+-%.0f %%): inspect its propeller and motor now" % (100 * band)
        else:
            text += "; it leaves the healthy band (+-%.0f %%) in about %.0f flights: inspect its propeller" % (
                100 * band, story["leaves_in"])
        return Finding(vehicle, "motor %d" % channel, "wear", text)
    if story["story"] == "drift":
        return Finding(vehicle, "motor %d" % channel, "drift",
                       "%s drifts: its thrust rises %.2f %% per flight after %s, now %.1f %% of its "
                       "reference: the reference may not be this vehicle's" % (
                           where, 100 * story["rate"], flight(story["onset"]), 100 * story["now"]))
    if story["story"] == "step":
        text = ("%s stepped from %.1f %% to %.1f %% of its reference at %s: a part changed (a new "
                "propeller or motor); a step, not wear" % (where, 100 * story["before"], 100 * story["after"],
                                                           flight(story["at"])))
        if "then" in story and story["then"]["rate"] < 0:
            text += ", and it wears since: %.2f %% per flight" % (-100 * story["then"]["rate"])
        text += ("; outside the healthy band: inspect it" if story["outside"] else
                 "; if it was maintenance, learn a new reference from the flights since")
        return Finding(vehicle, "motor %d" % channel, "step", text, attention=story["outside"] or "then" in story)
    if story["story"] == "stable" and story.get("outside"):
        return Finding(vehicle, "motor %d" % channel, "outside",
                       "%s gives %.1f %% of its reference thrust on every flight, outside the healthy band (+-%.0f %%):"
                       " inspect it, or learn the reference again if the vehicle was rebuilt" % (
                           where, 100 * story["now"], 100 * band))
    return None


def _change(story):
    """A story's change as (flight it starts at, signed size per flight or step), or None."""
    if story["story"] == "drift":
        return story["onset"], story["rate"]
    if story["story"] == "step":
        return story["at"], story["after"] - story["before"]
    return None


def mirrors(rotors):
    """Pairs (falling, rising) of rotors whose stories are one change seen twice: a quad's moment
    balance cannot tell a weaker rotor from a stronger diagonal partner, so one rotor losing thrust
    reads as its partner gaining as much, from the same flight. Returns {rising: falling}."""
    out = {}
    changes = {channel: _change(rotor["story"]) for channel, rotor in rotors.items()}
    for low, low_change in changes.items():
        if not low_change or low_change[1] >= 0:
            continue
        for high, high_change in changes.items():
            if high in out or not high_change or high_change[1] <= 0:
                continue
            if (rotors[low]["story"]["story"] == rotors[high]["story"]["story"] and
                    abs(low_change[0] - high_change[0]) <= 2 and
                    abs(abs(low_change[1]) - high_change[1]) <= 0.35 * abs(low_change[1])):
                out[high] = low
                break
    return out


def analyse(fleet, flights):
    """Per vehicle: its flights in order, its rotors' series and stories, its packs' and the
    findings; and the fleet's findings in vehicle order. Returns (vehicles dict, findings list)."""
    vehicles = {}
    findings = []
    flights = ordered(flights)
    for name in sorted(set(fleet.vehicles) | {f["vehicle"] for f in flights}):
        own = [f for f in flights if f["vehicle"] == name]
        for number, f in enumerate(own, start=1):
            f["number"] = number
        estimated = [f for f in own if f["status"] != "refused"]
        judged = [f for f in estimated if f["rotors"]]
        channels = sorted({r["channel"] for f in judged for r in f["rotors"]})
        rotors = {}
        for channel in channels:
            series = [(f, r) for f in judged for r in f["rotors"] if r["channel"] == channel]
            story = trends.judge([r["factor"] for _, r in series], band=fleet.healthy_band)
            rotors[channel] = {"flights": [f for f, _ in series], "factors": [r for _, r in series], "story": story}
        mirrored = mirrors(rotors)
        for channel, rotor in rotors.items():
            if channel in mirrored:
                rotor["mirror_of"] = mirrored[channel]
                continue
            finding = rotor_line(name, channel, rotor["story"], rotor["flights"], fleet.healthy_band)
            if finding:
                partner = [high for high, low in mirrored.items() if low == channel]
                if partner:
                    finding.line += (" (motor %d reads the mirror image, rising as much: the moment balance cannot tell "
                                     "a weaker rotor from a stronger diagonal partner, and a rotor does not gain thrust "
                                     "by itself)" % partner[0])
                findings.append(finding)
        packs = {}
        for pack in sorted({f["pack"] for f in estimated if f["pack"]}):
            series = [f for f in estimated if f["pack"] == pack and f["pack_resistance_ohm"] is not None]
            story = trends.pack_ageing([f["pack_resistance_ohm"] for f in series])
            packs[pack] = {"flights": series, "story": story}
            if story["ageing"]:
                findings.append(Finding(name, "pack %s" % pack, "pack_ageing",
                                        "pack %s (vehicle %s) is ageing: its resistance rose %.0f %% over its %d flights "
                                        "(%.1f to %.1f mOhm, %.2f mOhm per flight): less power and hover time; plan its "
                                        "replacement" % (pack, name, 100 * story["growth"], len(series),
                                                         1e3 * story["level"], 1e3 * story["now"], 1e3 * story["rate"])))
        for f in own:
            if f["status"] == "refused":
                findings.append(Finding(name or "?", os.path.basename(f["log"]), "refused",
                                        "%s: refused: %s" % (f["log"], f["problem"]), attention=False))
            elif f["status"] == "damaged":
                findings.append(Finding(name, os.path.basename(f["log"]), "damaged",
                                        "%s: estimated up to its damage: %s" % (f["log"], f["problem"]), attention=False))
        vehicles[name] = {"flights": own, "estimated": estimated, "rotors": rotors, "packs": packs,
                          "described": name in fleet.vehicles,
                          "reference": any(f["reference"] == "vehicle" for f in estimated)}
    return vehicles, findings
