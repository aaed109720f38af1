#!/usr/bin/env python3
"""Draws the figures of fit_surfaces' and compare_models' reports from the CSV files they write.

Usage: plot_bench_report.py fit DIR       (fit_*.csv -> fit_*.png)
       plot_bench_report.py compare DIR   (compare_*.csv -> compare_*.png)
       plot_bench_report.py gap DIR       (gap_samples.csv -> gap_*.png, diagnose_gap)
       plot_bench_report.py estimate DIR  (estimates.csv -> mass.png, estimate)

The C++ tools compute every number; this script only draws. Needs matplotlib and numpy (Debian's
python3-matplotlib).
"""
import csv
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

LABELS = {"thrust": "Thrust", "current": "Current", "power": "Electrical power", "efficiency": "Efficiency",
          "rpm": "Speed"}
DPI = 110



def cell(text):
    """A number from a report CSV cell; an empty cell (outside the covered domain) is NaN, a gap."""
    return float(text) if text != "" else float("nan")

def read_rows(directory, name):
    with open(os.path.join(directory, name), newline="") as handle:
        return list(csv.DictReader(handle))


def axis_label(output, unit):
    return "%s (%s)" % (LABELS[output], unit)


def panel_grid(count, title):
    columns = 3 if count > 4 else 2
    rows = (count + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(5.2 * columns, 4.0 * rows), squeeze=False)
    for extra in axes.flat[count:]:
        extra.set_visible(False)
    figure.suptitle(title, fontsize=14)
    return figure, list(axes.flat[:count])


def level_colours(values):
    values = sorted(values)
    cmap = plt.get_cmap("viridis")
    span = (values[-1] - values[0]) or 1.0
    return {value: cmap(0.9 * (value - values[0]) / span) for value in values}


def contour_label(value):
    return "%.0f" % value if abs(value) >= 100 else "%.3g" % value


def save(figure, directory, name):
    figure.tight_layout(rect=(0, 0, 1, 0.95))
    figure.savefig(os.path.join(directory, name), dpi=DPI)
    plt.close(figure)


# ---- fit_surfaces ---------------------------------------------------------------------------------

def plot_fit(directory):
    units = OrderedDict((row["output"], row["unit"]) for row in read_rows(directory, "fit_outputs.csv")
                        if row["source"] != "none")
    points = read_rows(directory, "fit_points.csv")
    pwm_curves = read_rows(directory, "fit_curves_pwm.csv")
    voltage_curves = read_rows(directory, "fit_curves_voltage.csv")
    grid = read_rows(directory, "fit_surface_grid.csv")
    outputs = list(units)
    by_level, by_pwm_level, by_output = {}, {}, {}
    for row in points:
        by_level.setdefault((row["output"], float(row["voltage_level_v"])), []).append(row)
        by_pwm_level.setdefault((row["output"], float(row["pwm_level_us"])), []).append(row)
        by_output.setdefault(row["output"], []).append(row)
    levels = sorted({level for (_, level) in by_level})
    colours = level_colours(levels)
    many_levels = len(levels) > 10

    # Outputs against PWM at each voltage level.
    figure, axes = panel_grid(len(outputs),
                              "Outputs against PWM at each voltage level: bench points and fitted sections")
    for axis, output in zip(axes, outputs):
        for level in levels:
            rows = by_level.get((output, level), [])
            on = [r for r in rows if r["off_level"] == "0"]
            off = [r for r in rows if r["off_level"] == "1"]
            axis.scatter([float(r["pwm_us"]) for r in on], [float(r["measured"]) for r in on], s=10,
                         color=colours[level], alpha=0.6)
            axis.scatter([float(r["pwm_us"]) for r in off], [float(r["measured"]) for r in off], s=22,
                         facecolors="none", edgecolors=colours[level])
            curve = [r for r in pwm_curves if r["output"] == output and float(r["voltage_v"]) == level]
            axis.plot([float(r["pwm_us"]) for r in curve], [cell(r["fitted"]) for r in curve], color=colours[level],
                      linewidth=1.6, label=None if many_levels else "%.2f V" % level)
        axis.set_xlabel("PWM (\u00b5s)")
        axis.set_ylabel(axis_label(output, units[output]))
        axis.set_title(LABELS[output])
        axis.grid(alpha=0.3)
    if not many_levels:
        axes[0].legend(title="voltage level", fontsize=8)
    save(figure, directory, "fit_sections_pwm.png")

    # Outputs against voltage at fixed PWM.
    pwm_levels = sorted({float(r["pwm_us"]) for r in voltage_curves})
    pwm_colours = {p: plt.get_cmap("plasma")(0.85 * k / max(1, len(pwm_levels) - 1)) for k, p in enumerate(pwm_levels)}
    figure, axes = panel_grid(len(outputs), "Outputs against voltage at fixed PWM: bench points and fitted sections")
    for axis, output in zip(axes, outputs):
        for pwm in pwm_levels:
            rows = by_pwm_level.get((output, pwm), [])
            axis.scatter([float(r["voltage_v"]) for r in rows], [float(r["measured_at_pwm_level"]) for r in rows],
                         s=10, color=pwm_colours[pwm], alpha=0.6)
            curve = [r for r in voltage_curves if r["output"] == output and float(r["pwm_us"]) == pwm]
            axis.plot([float(r["voltage_v"]) for r in curve], [cell(r["fitted"]) for r in curve],
                      color=pwm_colours[pwm], linewidth=1.6, label="%.0f \u00b5s" % pwm)
        axis.set_xlabel("Supply voltage (V)")
        axis.set_ylabel(axis_label(output, units[output]))
        axis.set_title(LABELS[output])
        axis.grid(alpha=0.3)
    axes[0].legend(title="PWM level", fontsize=8)
    save(figure, directory, "fit_sections_voltage.png")

    # Residuals.
    figure, axes = panel_grid(len(outputs), "Residuals (fitted - measured) against PWM, coloured by supply voltage")
    for axis, output in zip(axes, outputs):
        rows = by_output.get(output, [])
        residuals = np.array([float(r["residual"]) for r in rows])
        scatter = axis.scatter([float(r["pwm_us"]) for r in rows], residuals, s=10, alpha=0.7, cmap="viridis",
                               c=[float(r["voltage_v"]) for r in rows])
        axis.axhline(0.0, color="black", linewidth=0.8)
        rmse = float(np.sqrt(np.mean(residuals ** 2))) if len(residuals) else float("nan")
        axis.set_title("%s (RMSE %.3g %s)" % (LABELS[output], rmse, units[output]))
        axis.set_xlabel("PWM (\u00b5s)")
        axis.set_ylabel("Residual (%s)" % units[output])
        axis.grid(alpha=0.3)
        figure.colorbar(scatter, ax=axis, label="Voltage (V)")
    save(figure, directory, "fit_residuals.png")

    # Surfaces as contour maps.
    figure, axes = panel_grid(len(outputs), "Fitted surfaces over the domain, with the bench points")
    for axis, output in zip(axes, outputs):
        rows = [r for r in grid if r["output"] == output]
        pwms = sorted({float(r["pwm_us"]) for r in rows})
        volts = sorted({float(r["voltage_v"]) for r in rows})
        values = np.full((len(volts), len(pwms)), np.nan)
        pwm_index = {p: k for k, p in enumerate(pwms)}
        volt_index = {v: k for k, v in enumerate(volts)}
        for r in rows:
            values[volt_index[float(r["voltage_v"])], pwm_index[float(r["pwm_us"])]] = cell(r["value"])
        filled = axis.contourf(pwms, volts, values, levels=14, cmap="viridis")
        lines = axis.contour(pwms, volts, values, levels=7, colors="white", linewidths=0.6)
        axis.clabel(lines, fontsize=7, fmt=contour_label)
        data = by_output.get(output, [])
        axis.scatter([float(r["pwm_us"]) for r in data], [float(r["voltage_v"]) for r in data], s=9, color="black",
                     edgecolors="white", linewidths=0.5)
        figure.colorbar(filled, ax=axis, label=axis_label(output, units[output]))
        axis.set_xlabel("PWM (\u00b5s)")
        axis.set_ylabel("Supply voltage (V)")
        axis.set_title(LABELS[output])
    save(figure, directory, "fit_surfaces.png")


# ---- compare_models -------------------------------------------------------------------------------

def plot_compare(directory):
    curves = read_rows(directory, "compare_curves.csv")
    models = list(OrderedDict.fromkeys(r["model"] for r in curves))
    points = read_rows(directory, "compare_points.csv")
    hover = {r["model"]: r for r in read_rows(directory, "compare_hover.csv")}
    colours = {m: plt.get_cmap("tab10")(k % 10) for k, m in enumerate(models)}
    quantities = [("thrust_g", "thrust", "g"), ("current_a", "current", "A"), ("power_w", "power", "W"),
                  ("efficiency_g_per_w", "efficiency", "g/W"), ("rpm", "rpm", "rpm")]
    voltages = sorted({float(r["voltage_v"]) for r in curves})
    at = ("%.2f V" % voltages[0]) if len(voltages) == 1 else "each model's top voltage"
    figure, axes = panel_grid(6, "Comparison at %s: curves of the fitted models, bench points nearby" % at)
    for axis, (column, output, unit) in zip(axes, quantities):
        for model in models:
            rows = [r for r in curves if r["model"] == model and r[column] != ""]
            axis.plot([float(r["pwm_us"]) for r in rows], [float(r[column]) for r in rows], color=colours[model],
                      linewidth=1.6, label=model)
            near = [r for r in points if r["model"] == model and r[column] != ""]
            axis.scatter([float(r["pwm_us"]) for r in near], [float(r[column]) for r in near], s=12,
                         color=colours[model], alpha=0.6)
        axis.set_xlabel("PWM (\u00b5s)")
        axis.set_ylabel(axis_label(output, unit))
        axis.set_title(LABELS[output])
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    # Efficiency against thrust: what a propeller choice is about, with the hover thrust.
    axis = axes[5]
    for model in models:
        rows = [r for r in curves if r["model"] == model and r["efficiency_g_per_w"] != ""]
        axis.plot([float(r["thrust_g"]) for r in rows], [float(r["efficiency_g_per_w"]) for r in rows],
                  color=colours[model], linewidth=1.6, label=model)
    hover_thrust = [float(r["thrust_per_motor_g"]) for r in hover.values() if r["thrust_per_motor_g"] != ""]
    if hover_thrust:
        axis.axvline(hover_thrust[0], color="black", linestyle="--", linewidth=1.0,
                     label="hover thrust per motor")
    axis.set_xlabel("Thrust (g)")
    axis.set_ylabel("Efficiency (g/W)")
    axis.set_title("Efficiency against thrust")
    axis.grid(alpha=0.3)
    axis.legend(fontsize=8)
    save(figure, directory, "compare_curves.png")

    discharge = read_rows(directory, "compare_discharge.csv")
    if not discharge:
        return
    figure, (left, right) = plt.subplots(1, 2, figsize=(12, 4.4))
    figure.suptitle("Hover on the battery: total current during the discharge, and endurance", fontsize=14)
    for model in models:
        rows = [r for r in discharge if r["model"] == model]
        left.plot([float(r["time_min"]) for r in rows], [float(r["total_current_a"]) for r in rows],
                  color=colours[model], linewidth=1.6, label=model)
    left.set_xlabel("Hover time (min)")
    left.set_ylabel("Total hover current (A)")
    left.grid(alpha=0.3)
    left.legend(fontsize=8, loc="upper left")
    names = [m for m in models if hover.get(m, {}).get("endurance_min", "") != ""]
    values = [float(hover[m]["endurance_min"]) for m in names]
    bars = right.bar(range(len(names)), values, color=[colours[m] for m in names])
    right.bar_label(bars, fmt="%.1f", fontsize=8)
    right.set_xticks(range(len(names)))
    right.set_xticklabels(names, rotation=30, ha="right", fontsize=8)
    right.set_ylabel("Hover endurance (min)")
    right.grid(alpha=0.3, axis="y")
    save(figure, directory, "compare_endurance.png")


def column(rows, name):
    return np.array([float(r[name]) if r[name] != "" else np.nan for r in rows])


def plot_gap(directory):
    rows = read_rows(directory, "gap_samples.csv")
    selected = [r["name"] for r in read_rows(directory, "gap_selected.csv")]
    truth = column(rows, "truth_n")
    model = 100.0 * (column(rows, "model_n") / truth - 1.0)
    current = 100.0 * (column(rows, "current_view_n") / truth - 1.0)
    corrected = 100.0 * (column(rows, "corrected_n") / truth - 1.0)
    predicted = model - corrected
    # The diagnosis's correction holds more than the named effects (the vehicle's own, the healthy
    # level, a suspect motor's factor): drawn whenever it differs from the plain model, and said so.
    change = np.abs(corrected - model)
    corrected_differs = bool(np.any(change[np.isfinite(change)] > 1e-6))
    corrected_name = ("with " + ", ".join(selected)) if selected else "corrected (no effect named)"
    signals = [("pwm_us", "Mean pulse width (us)"), ("voltage_v", "Battery voltage (V)"),
               ("current_a", "Battery current (A)"), ("height_m", "Height above ground (m)"),
               ("vertical_speed_m_s", "Vertical speed (m/s)"), ("air_density_kg_m3", "Air density (kg/m^3)"),
               ("motor_temperature_c", "Motor temperature (deg C)"), ("flight_time_s", "Time in flight (s)")]
    present = [(name, label) for name, label in signals if np.isfinite(column(rows, name)).any()]
    figure, axes = panel_grid(len(present), "Residual of the model (PWM view) against each signal")
    for axis, (name, label) in zip(axes, present):
        x = column(rows, name)
        axis.scatter(x, model, s=4, alpha=0.35, label="model - truth")
        if corrected_differs:
            axis.scatter(x, predicted, s=4, alpha=0.35, color="tab:orange",
                         label="predicted by " + (", ".join(selected) if selected else "the correction (no effect named)"))
        axis.axhline(0.0, color="black", linewidth=0.6)
        axis.set_xlabel(label)
        axis.set_ylabel("Residual (% of truth)")
        # Five ticks at most: air density spans a few thousandths and its labels would collide.
        axis.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(5))
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="best")
    save(figure, directory, "gap_signals.png")

    rpm = 100.0 * (column(rows, "rpm_view_n") / truth - 1.0) if "rpm_view_n" in rows[0] else np.full_like(model, np.nan)
    has_rpm = np.isfinite(rpm).any()
    figure, axes = plt.subplots(1, 2 if has_rpm else 1, figsize=(12.8 if has_rpm else 6.4, 5.6), squeeze=False)
    views = [(current, "Current-view residual (% of truth)", "Two views of the thrust" if not has_rpm else
              "PWM view against the current view",
              ((1.0, "thrust loss, hidden mass, ground effect, climb"),
               (1.0 / 3.0, "supply resistance, air density (about three to one)"),
               (0.0, "ESC offset"), (-1.0, "motor temperature (opposite)")),
              "no measured battery current or no current surface")]
    if has_rpm:
        views.append((rpm, "RPM-view residual (% of truth)", "PWM view against the RPM view (ESC telemetry)",
                      ((1.0, "thrust loss, hidden mass, ground effect, climb, translational lift"),
                       (0.0, "ESC offset, supply resistance, air density, motor temperature")), ""))
    for axis, (view, label, title, lines, missing) in zip(axes[0], views):
        finite = np.isfinite(view)
        if finite.any():
            axis.scatter(model[finite], view[finite], s=5, alpha=0.4)
            span = np.nanmax(np.abs(model[finite])) * 1.1 + 0.5
            line = np.array([-span, span])
            for slope, name in lines:
                axis.plot(line, slope * line, linewidth=1.0, label=name)
            axis.set_ylim(-span * 1.5, span * 1.5)
            axis.legend(fontsize=8, loc="best")
        else:
            axis.text(0.5, 0.5, missing, ha="center", transform=axis.transAxes)
        axis.axhline(0.0, color="black", linewidth=0.6)
        axis.axvline(0.0, color="black", linewidth=0.6)
        axis.set_xlabel("PWM-view residual (% of truth)")
        axis.set_ylabel(label)
        axis.set_title(title)
        axis.grid(alpha=0.3)
    save(figure, directory, "gap_two_views.png")

    flights = column(rows, "flight").astype(int)
    time = column(rows, "time_s")
    figure, (left, right) = plt.subplots(1, 2, figsize=(12.0, 4.4))
    for flight in sorted(set(flights)):
        mask = flights == flight
        left.plot(time[mask], model[mask], ".", markersize=2, label="flight %d plain" % (flight + 1))
        if corrected_differs:
            left.plot(time[mask], corrected[mask], ".", markersize=2, label="flight %d corrected" % (flight + 1))
    left.axhline(0.0, color="black", linewidth=0.6)
    left.set_xlabel("Time in the log (s)")
    left.set_ylabel("Residual (% of truth)")
    left.grid(alpha=0.3)
    left.legend(fontsize=7, loc="best", ncol=2)
    bins = np.linspace(np.nanmin([model.min(), corrected.min()]), np.nanmax([model.max(), corrected.max()]), 60)
    right.hist(model, bins=bins, alpha=0.6, label="plain model")
    if corrected_differs:
        right.hist(corrected, bins=bins, alpha=0.6, label=corrected_name)
    right.set_xlabel("Residual (% of truth)")
    right.set_ylabel("Blocks")
    right.grid(alpha=0.3)
    right.legend(fontsize=8)
    save(figure, directory, "gap_before_after.png")


# ---- estimate -------------------------------------------------------------------------------------

def hover_spans(time, hovering):
    """The stretches of consecutive hovering rows, as (start, end) times."""
    spans, start = [], None
    for t, h in zip(time, hovering):
        if h and start is None:
            start = t
        if not h and start is not None:
            spans.append((start, previous))
            start = None
        previous = t
    if start is not None:
        spans.append((start, time[-1]))
    return spans


def plot_estimate(directory):
    rows = read_rows(directory, "estimates.csv")
    figure, (top, bottom) = plt.subplots(2, 1, figsize=(11, 7), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    if not rows:
        top.text(0.5, 0.5, "no RCOut message was estimated (see summary.md)", ha="center", transform=top.transAxes)
        save(figure, directory, "mass.png")
        return
    # A pause longer than a second (disarmed on the ground) breaks the lines instead of bridging it.
    rows = [dict(r) for r in rows]
    broken = []
    for previous, row in zip([None] + rows[:-1], rows):
        if previous is not None and float(row["time_s"]) - float(previous["time_s"]) > 1.0:
            broken.append({key: ("" if key not in ("time_s", "hovering") else value) for key, value in previous.items()})
            broken[-1]["hovering"] = "0"
        broken.append(row)
    rows = broken
    time = column(rows, "time_s")
    hovering = column(rows, "hovering") == 1.0
    for k, (start, end) in enumerate(hover_spans(time, hovering)):
        for axis in (top, bottom):
            axis.axvspan(start, end, color="tab:green", alpha=0.12, label="hover" if k == 0 and axis is top else None)
    top.plot(time, column(rows, "lifted_mass_kg"), color="0.6", linewidth=0.6, label="mass the thrust holds (each message)")
    top.plot(time, column(rows, "total_mass_kg"), color="tab:blue", linewidth=1.8, label="hover average (total mass)")
    payload = column(rows, "payload_kg")
    if np.isfinite(payload).any():
        top.plot(time, payload, color="tab:orange", linewidth=1.8, label="payload")
    averaged = column(rows, "total_mass_kg")[hovering]
    if np.isfinite(averaged).any():
        # The hover masses and payloads fill the axis; the transients of take-off and landing may leave it.
        low = min(0.0, np.nanmin(payload)) if np.isfinite(payload).any() else 0.0
        high = np.nanmax(averaged)
        pad = 0.15 * (high - low)
        top.set_ylim(low - pad, high + 2.0 * pad)
    top.set_ylabel("Mass (kg)")
    top.grid(alpha=0.3)
    top.legend(fontsize=8, loc="upper left")
    top.set_title("Mass and payload over the flight; hover windows shaded")
    bottom.plot(time, column(rows, "voltage_v"), color="tab:red", linewidth=1.2)
    bottom.set_ylabel("Battery (V)")
    bottom.set_xlabel("Time from the log's start (s)")
    bottom.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(os.path.join(directory, "mass.png"), dpi=DPI)
    plt.close(figure)


def main(argv):
    modes = {"fit": plot_fit, "compare": plot_compare, "gap": plot_gap, "estimate": plot_estimate}
    if len(argv) != 3 or argv[1] not in modes:
        sys.stderr.write(__doc__)
        return 2
    modes[argv[1]](argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
