"""Self-checks of scripts/independent_effects.py, the independent hidden-effect generator: its
truth model against the thesis' closed forms, its effects' defining properties, and its CSV.

    /usr/bin/python3 -m unittest -v tests/python/test_independent_effects.py   (from the source tree)
    /usr/bin/python3 tests/python/test_independent_effects.py
"""
import math
import os
import sys
import tempfile
import unittest

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import independent_effects as ie  # noqa: E402

# A short protocol for the fast checks: 20 s of multisines, 20 s of random steps.
SHORT = (("multisine", 20.0, None, None), ("random_steps", 20.0, 4.0, 2.5))


def step_inputs(duration, tick, x_before, x_after, step_time, power=0.0):
    """Constant power, and a deflection step (a ramp over one tick) at step_time."""
    count = int(round(duration / tick))
    deflection = np.where(np.arange(count + 1) * tick < step_time, x_before, x_after)
    return ie.Inputs(tick, np.full(count, power), deflection.astype(float))


def triangle_inputs(tick, vertices, steps_per_leg):
    """A deflection through `vertices` in straight legs of `steps_per_leg` ticks each, no power."""
    path = [vertices[0]]
    for a, b in zip(vertices[:-1], vertices[1:]):
        path.extend(np.linspace(a, b, steps_per_leg + 1)[1:])
    path = np.asarray(path)
    return ie.Inputs(tick, np.zeros(len(path) - 1), path)


class TruthModel(unittest.TestCase):
    def test_sls_relaxes_with_time_constant_c_over_k2(self):
        # (7.6) at constant x after a step: F_l - k1 x = k2 dx exp(-(t - t0) k2 / c).
        truth = ie.Truth()
        inputs = step_inputs(12.0, 0.01, 15e-3, 25e-3, 1.0)
        times = np.arange(2.0, 11.0, 0.05)
        trace = ie.simulate(inputs, truth, times=times)
        arm = trace.force_l - truth.k1 * trace.x
        slope = np.polyfit(times, np.log(arm), 1)[0]
        tau = -1.0 / slope
        self.assertLess(abs(tau / (truth.damping / truth.k2) - 1.0), 1e-4)
        self.assertTrue(np.all(arm > 0))

    def test_thermal_force_settles_at_kappa_P_P_over_kappa_c(self):
        # (7.1) under constant P: F_T(t) = (kappa_P P / kappa_c) (1 - exp(-kappa_c t)).
        truth = ie.draw_truth(3)
        power = 2.0
        inputs = step_inputs(300.0, 0.05, 20e-3, 20e-3, 0.0, power)
        times = np.array([5.0, 20.0, 299.0])
        trace = ie.simulate(inputs, truth, times=times)
        steady = truth.kappa_P * power / truth.kappa_c
        expected = steady * (1.0 - np.exp(-truth.kappa_c * times))
        np.testing.assert_allclose(trace.thermal_force, expected, rtol=1e-6)
        self.assertAlmostEqual(trace.thermal_force[-1] / steady, 1.0, places=9)
        # the temperature ch7_base.yaml reports: T = T_amb + F_T / phi_T
        self.assertAlmostEqual(trace.temperature[-1], ie.AMBIENT + steady / ie.FORCE_PER_KELVIN)

    def test_coil_law_is_7_3_and_7_4_inverts_it(self):
        truth = ie.Truth()
        inputs = step_inputs(2.0, 0.05, 12e-3, 28e-3, 1.0)
        trace = ie.simulate(inputs, truth, times=np.array([0.5, 1.5]))
        _, coil = ie.outputs(trace)
        measure = coil - truth.lambda_0
        x = (truth.lambda_l - truth.lambda_x * measure) / measure   # (7.4)
        np.testing.assert_allclose(x, [12e-3, 28e-3], rtol=1e-12)


class Effects(unittest.TestCase):
    def pi_force_at_ticks(self, effect, tick):
        inputs = triangle_inputs(tick, [20e-3, 28e-3, 14e-3, 26e-3, 17e-3, 23e-3], 40)
        trace = ie.simulate(inputs, ie.Truth(), (effect,), times=inputs.tick_times[:-1])
        return effect.force(trace, trace.states[0]), trace

    def test_play_operator_hysteresis_is_rate_independent(self):
        effect = ie.PrandtlIshlinskii()
        slow, _ = self.pi_force_at_ticks(effect, 0.5)
        fast, _ = self.pi_force_at_ticks(effect, 0.02)
        np.testing.assert_array_equal(slow, fast)
        bound = sum(w * r for w, r in zip(effect.weights, effect.radii))
        self.assertLessEqual(np.abs(slow).max(), bound + 1e-15)

    def test_bouc_wen_is_rate_independent(self):
        effect = ie.BoucWen()
        slow, _ = self.pi_force_at_ticks(effect, 0.5)
        fast, _ = self.pi_force_at_ticks(effect, 0.02)
        np.testing.assert_allclose(slow, fast, rtol=0, atol=1e-9)
        self.assertLessEqual(np.abs(slow).max(), effect.stiffness * effect.z_max * (1 + 1e-6))
        # dissipative: a cycle of 8 mm about 20 mm takes work, less than the rectangle's
        angle = np.linspace(0.0, 4.5 * np.pi, 2251)
        x = 20e-3 + 8e-3 * np.sin(angle)
        inputs = ie.Inputs(0.01, np.zeros(len(x) - 1), x)
        trace = ie.simulate(inputs, ie.Truth(), (effect,), times=inputs.tick_times)
        force = effect.force(trace, trace.states[0])
        cycle = slice(1250, 2251)   # 5 pi/2 to 9 pi/2
        work = np.sum(0.5 * (force[cycle][1:] + force[cycle][:-1]) * np.diff(x[cycle]))
        self.assertGreater(work, 0.0)
        self.assertLess(work, 4 * 8e-3 * effect.stiffness * effect.z_max)

    def test_play_operator_loop_area_is_positive_and_as_derived(self):
        # A cycle of amplitude A about 20 mm after a first rise: sum_i 4 w_i r_i (A - r_i).
        effect, amplitude = ie.PrandtlIshlinskii(), 8e-3
        x = 20e-3 + amplitude * np.sin(np.linspace(0.0, 2.5 * np.pi, 20001))
        force = effect.force_of_path(x)
        cycle = slice(4000, 20001)   # from the first maximum (pi/2) once round (5 pi/2)
        # the work done on it, the loop's area: positive when loading runs above unloading
        work = np.sum(0.5 * (force[cycle][1:] + force[cycle][:-1]) * np.diff(x[cycle]))
        expected = sum(4 * w * r * (amplitude - r) for w, r in zip(effect.weights, effect.radii))
        self.assertGreater(work, 0.0)
        self.assertAlmostEqual(work / expected, 1.0, delta=1e-3)

    def test_ratchet_never_decreases(self):
        inputs = ie.make_inputs(4, protocol=SHORT)
        truth = ie.draw_truth(4)
        for effect in (ie.LinearRatchet(rate=1e-5, threshold_rise=5.0),
                       ie.SaturatingRatchet(rate=1e-5, threshold_rise=5.0, limit=0.5e-3)):
            with self.subTest(form=effect.form):
                trace = ie.simulate(inputs, truth, (effect,))
                length = trace.states[0][0]
                self.assertGreater(length[-1], 1e-5)                      # it grew
                self.assertGreaterEqual(np.diff(length).min(), -1e-12)    # never back (solver tol.)
                self.assertTrue(np.all(effect.force(trace, trace.states[0]) <= 1e-15))

    def test_every_form_runs_and_moves_an_output(self):
        # 30 s of deflection steps, and 3 W but for a dip to 1 W at 15-22 s: hot enough for the
        # ratchets' thresholds, and a power step for the lags
        steps = ie.make_inputs(2, protocol=(("random_steps", 30.0, 4.0, 2.5),))
        ticks = steps.tick_times[:-1]
        power = np.where((ticks >= 15.0) & (ticks < 22.0), 1.0, 3.0)
        inputs = ie.Inputs(steps.tick, power, steps.deflection)
        truth = ie.draw_truth(2)
        force0, coil0 = ie.outputs(ie.simulate(inputs, truth))
        for name, forms in ie.FORMS.items():
            for form in forms:
                with self.subTest(effect=name, form=form.form):
                    effect = form.make(1.0, np.random.default_rng(0))
                    trace = ie.simulate(inputs, truth, (effect,))
                    force, coil = ie.outputs(trace, (effect,))
                    change = max(np.abs(force - force0).max() / 1e-3,
                                 np.abs(coil - coil0).max() / 1e-3)
                    self.assertGreater(change, 0.1, "mN or 1e-3 of L*")
                    self.assertTrue(np.all(np.isfinite(force)) and np.all(np.isfinite(coil)))


class Measurement(unittest.TestCase):
    def case(self, seed, effect="hysteresis"):
        return ie.make_case(effect, seed, 2, inputs=ie.make_inputs(seed, protocol=SHORT))

    def test_csv_has_tcpmsims_headings_and_readings_on_their_grids(self):
        case = self.case(1)
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "measured.csv")
            ie.write_case(case, path)
            with open(path, encoding="utf-8") as file:
                lines = file.read().splitlines()
            data = ie.read_csv(path)
        header = [line for line in lines if not line.startswith("#")][0]
        self.assertEqual(header, "time[s],power[W],deflection[mm],force[mN],inductance_measure[1]")
        self.assertEqual(len(data["time[s]"]), 40 * 16 + 1)   # 0 to 40 s, both ends
        self.assertTrue(all(len(line.split(",")) == 5 for line in lines if not line.startswith("#")))
        np.testing.assert_allclose(np.diff(data["time[s]"]), 1 / 16)
        force = data["force[mN]"]
        np.testing.assert_array_equal(force * 2, np.round(force * 2))        # 0.5 mN grid
        deflection = data["deflection[mm]"]
        np.testing.assert_allclose(deflection / 0.02, np.round(deflection / 0.02), atol=1e-6)
        residual = force - 1e3 * case.force
        self.assertAlmostEqual(np.std(residual), math.hypot(2.0, 0.5 / math.sqrt(12)), delta=0.25)
        self.assertTrue(np.all((data["power[W]"] >= 0.10) & (data["power[W]"] <= 3.12)))

    def test_a_seed_gives_the_same_data_and_another_seed_others(self):
        a, b, c = self.case(7), self.case(7), self.case(8)
        for channel in a.readings:
            np.testing.assert_array_equal(a.readings[channel], b.readings[channel])
        self.assertEqual(a.definition, b.definition)
        self.assertFalse(np.array_equal(a.readings["force"], c.readings["force"]))

    def test_a_correlated_noise_is_first_order_and_leaves_the_white_part(self):
        seed = 3
        inputs = ie.make_inputs(seed, protocol=SHORT)
        white = ie.make_case("none", seed, 2, inputs=inputs)
        both = ie.make_case("none", seed, 2, inputs=inputs, correlated=(1.5, 0.5))
        self.assertEqual(both.definition["correlated_noise_mN"], 1.5)
        self.assertAlmostEqual(both.definition["force_noise_floor_mN"],
                               math.sqrt(4 + 2.25 + 0.25 / 12))
        self.assertNotIn("correlated_noise_mN", white.definition)
        # The correlated part alone, as drawn (its stream is its own).
        times = np.arange(0, 2000.0, 1 / 16)
        part = ie.correlated_noise(times, 1.5, 0.5, np.random.default_rng(5))
        effective = len(times) * (1 - math.exp(-1 / 8)) / (1 + math.exp(-1 / 8))
        self.assertAlmostEqual(np.std(part), 1.5, delta=4 * 1.5 / math.sqrt(2 * effective))
        for lag in (1, 2, 8):
            rho = np.dot(part[lag:], part[:-lag]) / np.dot(part, part)
            self.assertAlmostEqual(rho, math.exp(-lag / 16 / 0.5), delta=4 / math.sqrt(effective))
        # Readings differ from the white case's by the wander and the rounding only.
        difference = both.readings["force"] - white.readings["force"]
        self.assertGreater(np.std(difference), 1e-3)
        np.testing.assert_array_equal(both.readings["inductance_measure"],
                                      white.readings["inductance_measure"])


if __name__ == "__main__":
    unittest.main()
