"""fleet's trends: a series' story told from its own scatter (scripts/fleet_lib/trends.py)."""
import random

import pytest

from fleet_lib import trends


def noisy(values, sigma, seed):
    rng = random.Random(seed)
    return [v + rng.gauss(0.0, sigma) for v in values]


@pytest.mark.parametrize("seed", range(200))
def test_a_steady_series_is_stable(seed):
    story = trends.judge(noisy([1.0] * 30, 0.006, seed), band=0.05)
    assert story["story"] == "stable", story
    assert not story["outside"]


def test_too_few_flights_judge_nothing():
    assert trends.judge([1.0, 0.9, 0.8, 0.7, 0.6], band=0.05)["story"] == "too_few"


def test_wear_after_healthy_flights_is_a_drift_with_its_rate_and_its_way_out_of_the_band():
    values = noisy([1.0 - 0.004 * max(0, f - 8) for f in range(1, 21)], 0.004, 1)
    story = trends.judge(values, band=0.05)
    assert story["story"] == "drift"
    assert story["rate"] == pytest.approx(-0.004, abs=0.001)
    assert 6 <= story["onset"] <= 9
    assert not story["outside"] and 0 < story["leaves_in"] < 8


def test_a_part_swapped_is_a_step_not_a_drift():
    values = noisy([1.0] * 15 + [0.96] * 15, 0.005, 2)
    story = trends.judge(values, band=0.05)
    assert story["story"] == "step"
    assert story["at"] == 15
    assert story["after"] - story["before"] == pytest.approx(-0.04, abs=0.006)
    assert "then" not in story


def test_a_new_part_that_then_wears_is_a_step_then_a_drift():
    values = noisy([1.0] * 12 + [1.04 - 0.005 * f for f in range(18)], 0.003, 3)
    story = trends.judge(values, band=0.05)
    assert story["story"] == "step" and story["at"] == 12
    assert story["then"]["story"] == "drift" and story["then"]["rate"] < 0


def test_one_wild_flight_is_no_story():
    values = noisy([1.0] * 30, 0.005, 4)
    values[14] -= 0.08
    assert trends.judge(values, band=0.05)["story"] == "stable"


def test_a_steady_rotor_outside_the_band_says_so():
    story = trends.judge(noisy([0.93] * 20, 0.004, 5), band=0.05)
    assert story["story"] == "stable" and story["outside"] and story["leaves_in"] == 0


def test_a_pack_whose_resistance_grows_ages_and_one_that_scatters_does_not():
    growing = noisy([0.020 * (1 + 0.04 * f) for f in range(15)], 0.0008, 6)
    assert trends.pack_ageing(growing)["ageing"]
    assert trends.pack_ageing(growing)["growth"] == pytest.approx(0.56, abs=0.15)
    assert not trends.pack_ageing(noisy([0.020] * 15, 0.0015, 7))["ageing"]


def heavy_tailed(rng, scale):
    """Student's t with 3 degrees of freedom: flights with gusts and mis-hung payloads."""
    chi2 = sum(rng.gauss(0, 1) ** 2 for _ in range(3)) / 3
    return scale * rng.gauss(0, 1) / chi2 ** 0.5


def test_noise_rarely_makes_a_story_and_wear_is_told_before_it_leaves_the_band():
    series = 2000
    gaussian = sum(trends.judge(noisy([1.0] * 30, 0.006, seed), band=0.05)["story"] != "stable"
                   for seed in range(series))
    heavy = 0
    for seed in range(series):
        rng = random.Random(seed)
        heavy += trends.judge([1.0 + heavy_tailed(rng, 0.004) for _ in range(30)], band=0.05)["story"] != "stable"
    told = 0
    for seed in range(500):
        story = trends.judge(noisy([1.0 - 0.0035 * max(0, f - 8) for f in range(1, 21)], 0.006, seed), band=0.05)
        told += story["story"] == "drift" and story["rate"] < 0 and not story["outside"]
    print("stories out of noise: %.2f %% Gaussian, %.2f %% heavy-tailed; wear told by flight 20: %.1f %%" % (
        100 * gaussian / series, 100 * heavy / series, 100 * told / 500))
    assert gaussian / series <= 0.001
    assert heavy / series <= 0.005
    assert told / 500 >= 0.9
