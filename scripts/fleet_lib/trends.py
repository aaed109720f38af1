"""Trends over a vehicle's flights (docs/fleet.md#trends): each rotor's factor against its healthy
reference, and each pack's resistance. A series is judged against its own scatter, read from
its flight-to-flight differences (a drift or one step barely moves them), and one of three
stories is kept: stable; a step (a part changed: a new propeller, a motor swapped); a drift (a
flat stretch, then a steady slope: wear), with how fast it moves and when it leaves the healthy
band. Plain Python: a few dozen points per series."""
import math

# Evidence a story needs over "stable": its drop in squared residuals in units of the scatter's
# variance (5.5 standard deviations for one added parameter). Measured on 5,000 series of 30
# flights each (test_trends.py prints it): a story out of Gaussian noise in 0.02 % of them, out of
# heavy-tailed noise (Student's t, 3 degrees of freedom) in 0.12 %; a wear of 0.35 % per flight
# under 0.6 % of scatter is told by its 18th flight in 90 % of series, by its 20th in 97 %.
MIN_EVIDENCE = 30.0
# What a step must explain beyond a drift (and the reverse) to be told apart from it: a step's one
# more free parameter (the break) costs about ln(30) = 3.4; 6 leaves a margin.
STORY_MARGIN = 6.0
MIN_FLIGHTS = 6  # fewer: no trend is judged
CLIP = 3.0  # scatters from its neighbours' median beyond which a flight is pulled in (tamed)
MIN_SEGMENT = 3  # flights on either side of a step
# A pack ages when its resistance rises with that evidence by at least this share over its flights.
MIN_PACK_GROWTH = 0.15


def scatter(values):
    """A robust standard deviation of one point from the flight-to-flight differences (their
    median absolute deviation, scaled to a Gaussian's standard deviation, over sqrt 2)."""
    diffs = [b - a for a, b in zip(values, values[1:])]
    if len(diffs) < 2:
        return float("nan")
    middle = _median(diffs)
    return 1.4826 * _median([abs(d - middle) for d in diffs]) / math.sqrt(2.0)


def _median(values):
    ordered = sorted(values)
    n = len(ordered)
    return ordered[n // 2] if n % 2 else 0.5 * (ordered[n // 2 - 1] + ordered[n // 2])


def _mean(values):
    return sum(values) / len(values)


def _rss_constant(values):
    m = _mean(values)
    return sum((v - m) ** 2 for v in values)


def _line(xs, ys):
    """Least-squares line through (xs, ys): intercept, slope, residual sum of squares, sum of
    squared deviations of xs (for the slope's standard error)."""
    mx, my = _mean(xs), _mean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    intercept = my - slope * mx
    rss = sum((y - intercept - slope * x) ** 2 for x, y in zip(xs, ys))
    return intercept, slope, rss, sxx


def best_step(values):
    """The single step that explains `values` best: (break index, level before, level after, RSS)."""
    best = None
    for k in range(MIN_SEGMENT, len(values) - MIN_SEGMENT + 1):
        rss = _rss_constant(values[:k]) + _rss_constant(values[k:])
        if best is None or rss < best[3]:
            best = (k, _mean(values[:k]), _mean(values[k:]), rss)
    return best


def best_drift(values):
    """The flat-then-sloped line that explains `values` best: (onset index, level, slope per flight,
    RSS, sum of squared deviations of the sloped stretch's x). Onset 0: a straight line throughout."""
    n = len(values)
    xs = list(range(n))
    best = None
    for onset in range(0, n - MIN_SEGMENT):
        # y = level + slope * max(0, x - onset): linear in (level, slope).
        hinge = [max(0.0, x - onset) for x in xs]
        level, slope, rss, sxx = _line(hinge, values)
        if best is None or rss < best[3]:
            best = (onset, level, slope, rss, sxx)
    return best


def best_step_drift(values):
    """A step followed by a slope (a new part that then wears): (break index, level before, level
    just after, slope per flight after, RSS, sum of squared deviations of the sloped stretch's x)."""
    best = None
    for k in range(MIN_SEGMENT, len(values) - MIN_SEGMENT + 1):
        xs = list(range(len(values) - k))
        after, slope, rss, sxx = _line(xs, values[k:])
        rss += _rss_constant(values[:k])
        if best is None or rss < best[4]:
            best = (k, _mean(values[:k]), after, slope, rss, sxx)
    return best


def tamed(values):
    """`values` with wild flights pulled in: a point further than CLIP scatters from the median of
    its five neighbours (itself included) is set at that distance, so that one gust, one bad log
    or one mis-hung payload cannot make a story, while a step or a drift, which its neighbours
    follow, is left as it is."""
    sigma = scatter(values)
    if not sigma > 0:
        return list(values)
    out = []
    for i, value in enumerate(values):
        centre = _median(values[max(0, i - 2):i + 3])
        out.append(min(max(value, centre - CLIP * sigma), centre + CLIP * sigma))
    return out


def judge(values, band=None, centre=1.0):
    """The story of a series (a list of floats in flight order). `band`: the healthy band's half
    width around `centre` (rotor factors), or None (pack resistance). Returns a dict: story
    ('too_few', 'stable', 'step', 'drift'), scatter, evidence, now (the fitted value at the last
    flight); for a step: at (the first flight after it, 0-based), before, after, and `then` (a
    drift story) when the new part then drifts; for a drift: onset, level, rate (per flight),
    rate_std; with a band: outside (now lies outside it) and leaves_in (flights until the fitted
    line leaves the band; 0 when outside already; None when it does not head out).

    The scatter is the larger of the flight-to-flight differences' (robust, blind to a slow drift
    or one step) and the kept story's residuals' (which a wild flight or a story the series does
    not follow raise): neither alone can make a story out of noise."""
    n = len(values)
    out = {"story": "too_few", "flights": n}
    if n < MIN_FLIGHTS:
        return out
    values = tamed(values)
    rss0 = _rss_constant(values)
    step = best_step(values)
    drift = best_drift(values)
    both = best_step_drift(values)
    floor = max(scatter(values), 1e-9) ** 2
    # Each story's residual variance (over its degrees of freedom) and evidence over "stable".
    sigma2 = max(floor, min(step[3] / (n - 3), drift[3] / (n - 3), both[4] / (n - 4)))
    step_evidence = (rss0 - step[3]) / sigma2
    drift_evidence = (rss0 - drift[3]) / sigma2
    both_evidence = (rss0 - both[4]) / sigma2
    out.update(scatter=sigma2 ** 0.5, mean=_mean(values))
    best_evidence = max(step_evidence, drift_evidence, both_evidence)
    if best_evidence < MIN_EVIDENCE:
        out.update(story="stable", evidence=best_evidence, now=_mean(values))
    elif both_evidence > max(step_evidence, drift_evidence) + STORY_MARGIN:
        k, before, after, slope, _, sxx = both
        now = after + slope * (n - 1 - k)
        out.update(story="step", evidence=both_evidence, at=k, before=before, after=after, now=now,
                   then={"story": "drift", "onset": k, "level": after, "rate": slope,
                         "rate_std": (sigma2 / sxx) ** 0.5 if sxx > 0 else float("inf"), "now": now})
    elif step_evidence > drift_evidence + STORY_MARGIN:
        out.update(story="step", evidence=step_evidence, at=step[0], before=step[1], after=step[2], now=step[2])
    else:
        onset, level, slope, _, sxx = drift
        now = level + slope * (n - 1 - onset)
        out.update(story="drift", evidence=drift_evidence, onset=onset, level=level, rate=slope,
                   rate_std=(sigma2 / sxx) ** 0.5 if sxx > 0 else float("inf"), now=now)
    if band is not None:
        low, high = centre - band, centre + band
        now = out["now"]
        out["outside"] = not low <= now <= high
        rate = out.get("rate", out.get("then", {}).get("rate"))
        if out["outside"]:
            out["leaves_in"] = 0
        elif rate:
            out["leaves_in"] = ((low if rate < 0 else high) - now) / rate
        else:
            out["leaves_in"] = None
    return out


def pack_ageing(values):
    """Whether a pack's resistance (ohm per flight, in flight order) rises: the drift story with
    at least MIN_PACK_GROWTH of growth from its first fitted value. Returns judge()'s dict with
    `growth` (share) and `ageing` (bool)."""
    out = judge(values)
    out["ageing"] = False
    if out["story"] == "drift" and out["rate"] > 0:
        start = out["level"]
        out["growth"] = (out["now"] - start) / start if start > 0 else float("inf")
        out["ageing"] = out["growth"] >= MIN_PACK_GROWTH
    return out
