"""The fleet report (docs/fleet.md#the-report): README.md with every vehicle in one table and what
to inspect and why, overview.png (every vehicle's rotor factors over its flights against the
healthy band), and a page (Markdown + PNG) per vehicle that needs attention."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import analysis  # noqa: E402

STORY = {"too_few": "too few flights", "stable": "stable", "step": "step", "drift": "drift"}


def _rotor_cell(rotors):
    cells = []
    for channel, rotor in sorted(rotors.items()):
        story = rotor["story"]
        text = "%d: %s" % (channel, STORY[story["story"]])
        if "now" in story:
            text += " %.1f %%" % (100 * story["now"])
        cells.append(text)
    return "<br>".join(cells) if cells else "not judged"


def _plot_rotors(axes, vehicle, band, title):
    for channel, rotor in sorted(vehicle["rotors"].items()):
        xs = [f["number"] for f in rotor["flights"]]
        ys = [100 * r["factor"] for r in rotor["factors"]]
        line, = axes.plot(xs, ys, ".-", linewidth=0.8, markersize=3, label="motor %d" % channel)
        story = rotor["story"]
        # The story's fit over the series' positions (the flights judged), drawn at their numbers.
        if story["story"] == "drift":
            fit = [story["level"] + story["rate"] * max(0, i - story["onset"]) for i in range(len(xs))]
            axes.plot(xs, [100 * v for v in fit], "-", color=line.get_color(), linewidth=2, alpha=0.6)
        elif story["story"] == "step":
            then = story.get("then")
            fit = [story["before"] if i < story["at"] else
                   (then["level"] + then["rate"] * (i - story["at"]) if then else story["after"]) for i in range(len(xs))]
            axes.plot(xs, [100 * v for v in fit], "--", color=line.get_color(), linewidth=2, alpha=0.6)
    axes.axhspan(100 * (1 - band), 100 * (1 + band), color="0.9", zorder=0)
    axes.set_title(title, fontsize=8)
    axes.tick_params(labelsize=6)


def _overview(path, vehicles, attention, band):
    names = sorted(vehicles)
    columns = 5
    rows = max(1, (len(names) + columns - 1) // columns)
    figure, grid = plt.subplots(rows, columns, figsize=(3 * columns, 2.2 * rows), sharey=True, squeeze=False)
    for index, name in enumerate(names):
        axes = grid[index // columns][index % columns]
        _plot_rotors(axes, vehicles[name], band, name + (" (inspect)" if name in attention else ""))
        if name in attention:
            axes.title.set_color("firebrick")
    for index in range(len(names), rows * columns):
        grid[index // columns][index % columns].axis("off")
    for axes in grid[:, 0]:
        axes.set_ylabel("rotor factor, % of reference", fontsize=7)
    grid[0][0].legend(fontsize=6, loc="lower left")
    figure.suptitle("Each vehicle's rotors over its flights against its healthy reference (band shaded)", fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)


def _vehicle_page(folder, name, vehicle, findings, band):
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6.5))
    _plot_rotors(top, vehicle, band, "%s: rotor factors (thin: each flight; thick: the trend kept; dashed: a step)" % name)
    top.set_xlabel("flight", fontsize=7)
    top.set_ylabel("% of reference thrust", fontsize=7)
    top.legend(fontsize=7)
    for pack, data in sorted(vehicle["packs"].items()):
        bottom.plot([f["number"] for f in data["flights"]], [1e3 * f["pack_resistance_ohm"] for f in data["flights"]],
                    ".-", label="pack %s%s" % (pack, " (ageing)" if data["story"]["ageing"] else ""))
    bottom.set_title("%s: pack resistance on the flights it flew" % name, fontsize=8)
    bottom.set_xlabel("flight", fontsize=7)
    bottom.set_ylabel("mOhm", fontsize=7)
    if vehicle["packs"]:
        bottom.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(folder, "vehicle_%s.png" % name), dpi=90)
    plt.close(figure)
    lines = ["# Vehicle %s" % name, "", "[Back to the fleet](README.md)", ""]
    lines += ["- " + f.line for f in findings]
    lines += ["", "![rotor factors and pack resistance](vehicle_%s.png)" % name, "", "## Flights", "",
              "| flight | pack | hover mass (kg) | rotor factors (% of reference) | pack resistance (mOhm) | status |",
              "|---|---|---|---|---|---|"]
    for f in analysis.ordered(vehicle["flights"]):
        factors = ", ".join("%d: %.1f" % (r["channel"], 100 * r["factor"]) for r in f["rotors"]) or "-"
        mass = "%.3f" % f["hover_mass_kg"] if f["hover_mass_kg"] is not None else "-"
        resistance = "%.1f" % (1e3 * f["pack_resistance_ohm"]) if f["pack_resistance_ohm"] is not None else "-"
        status = f["status"] if f["status"] == "estimated" else "%s: %s" % (f["status"], f["problem"])
        lines.append("| %s | %s | %s | %s | %s | %s |" % (os.path.basename(f["log"]), f["pack"] or "-", mass, factors,
                                                          resistance, status))
    with open(os.path.join(folder, "vehicle_%s.md" % name), "w") as handle:
        handle.write("\n".join(lines) + "\n")


def write(fleet, flights, problems):
    """Writes the report into fleet.report; returns its README's path."""
    folder = fleet.report
    os.makedirs(folder, exist_ok=True)
    for stale in os.listdir(folder):  # pages of vehicles that no longer need attention
        if stale.startswith("vehicle_") and stale.endswith((".md", ".png")):
            os.remove(os.path.join(folder, stale))
    vehicles, findings = analysis.analyse(fleet, flights)
    attention = sorted({f.vehicle for f in findings if f.attention})
    lines = ["# Fleet report", "",
             "%d vehicles, %d flights (%d refused), from `%s`. Each rotor's factor is its thrust against its share on "
             "the vehicle's healthy reference flights (100 %%: as then); the healthy band is +-%.0f %%." % (
                 len(vehicles), len(flights), sum(f["status"] == "refused" for f in flights),
                 os.path.relpath(fleet.database, os.path.dirname(os.path.abspath(fleet.path))),
                 100 * fleet.healthy_band), "", "## To inspect", ""]
    wanted = [f for f in findings if f.attention]
    lines += ["- **%s**: %s ([page](vehicle_%s.md))" % (f.vehicle, f.line, f.vehicle) for f in wanted] or ["Nothing."]
    notes = [f for f in findings if not f.attention and f.kind not in ("refused", "damaged")]
    if notes:
        lines += ["", "## To know", ""] + ["- %s: %s" % (f.vehicle, f.line) for f in notes]
    lines += ["", "![every vehicle's rotors](overview.png)", "", "## Vehicles", "",
              "| vehicle | flights | refused | reference | rotors: story, factor now | packs |", "|---|---|---|---|---|---|"]
    for name, vehicle in sorted(vehicles.items()):
        packs = ", ".join("%s%s" % (p, " ageing" if d["story"]["ageing"] else "") for p, d in sorted(
            vehicle["packs"].items())) or "-"
        refused = sum(f["status"] == "refused" for f in vehicle["flights"])
        reference = "its own" if vehicle["reference"] else ("none: judged against the ideal balance" if
                                                            vehicle["described"] else "not in the description")
        lines.append("| %s | %d | %d | %s | %s | %s |" % (name or "?", len(vehicle["flights"]), refused, reference,
                                                          _rotor_cell(vehicle["rotors"]), packs))
    problem_lines = list(problems.values()) + [f.line for f in findings if f.kind in ("refused", "damaged")]
    lines += ["", "## Logs with problems", ""] + (["- " + p for p in problem_lines] or ["None."])
    with open(os.path.join(folder, "README.md"), "w") as handle:
        handle.write("\n".join(lines) + "\n")
    _overview(os.path.join(folder, "overview.png"), {n: v for n, v in vehicles.items() if n}, attention,
              fleet.healthy_band)
    for name in attention:
        _vehicle_page(folder, name, vehicles[name], [f for f in findings if f.vehicle == name], fleet.healthy_band)
    return os.path.join(folder, "README.md")
