"""tcpmsim.Simulator and tcpmsim.env.MuscleEnv: a controller written in Python closes the loop.

Run by ctest with PYTHONPATH=<build>/python:tests/python, TCPMSIM=<the program> and the source
tree as the working directory."""

import math
import os
import subprocess
import tempfile
import unittest

import h5py
import numpy as np

import tcpmsim
from tcpmsim.env import MuscleEnv

FORCE_STEPS = "configs/ch7_control/force_steps.yaml"
EXTERNAL = "configs/ch7_control/external_force.yaml"
SHORT = {"scenario.duration": "60 s"}


def pid_power(reference, estimate, state, dt=0.05, kp=540.0, ti=1.0, low=0.10, high=3.12):
    """The thesis' PI (7.7)-(7.9), explicit Euler with back-calculation; idle while the estimate
    is undefined."""
    if not math.isfinite(estimate):
        state["integral"] = 0.0
        return low
    error = reference - estimate
    demand = kp * (error + state["integral"] / ti)
    power = min(high, max(low, demand))
    state["integral"] += dt * (error - (demand - power) / kp)
    return power


class SimulatorTest(unittest.TestCase):
    def test_python_pi_reproduces_the_builtin_pid_bit_for_bit(self):
        builtin = tcpmsim.Scenario.from_yaml(FORCE_STEPS, set=SHORT).run()
        simulator = tcpmsim.Simulator(tcpmsim.Scenario.from_yaml(EXTERNAL, set=SHORT))
        self.assertEqual(list(simulator.inputs()), ["controller.power_command"])
        # The reference the PID follows, as the external controller reports it at each sample.
        state = {"integral": 0.0}
        outputs = simulator.outputs()
        while not simulator.finished:
            power = pid_power(outputs["controller/reference"], outputs["estimator/force"], state)
            outputs = simulator.step({"controller.power_command": power}, 0.05)
        stepped = simulator.result()
        self.assertEqual(stepped.status, "complete")
        for channel in ("muscle/force", "muscle/temperature", "drive/power",
                        "drive/inductance_measure", "estimator/force",
                        "controller/power_command", "controller/reference"):
            with self.subTest(channel=channel):
                np.testing.assert_array_equal(stepped[channel], builtin[channel])

    def test_outputs_inputs_errors_and_reset(self):
        simulator = tcpmsim.Simulator(EXTERNAL)
        described = simulator.inputs()["controller.power_command"]
        self.assertEqual((described["unit"], described["low"], described["high"]),
                         ("W", 0.10, 3.12))
        outputs = simulator.step(2.0, 0.5)  # a bare number: the only input
        self.assertIsInstance(outputs["muscle/force"], float)
        self.assertAlmostEqual(simulator.time, 0.5)
        with self.assertRaisesRegex(ValueError, "outside its range"):
            simulator.set_input("controller.power_command", 5.0)
        with self.assertRaisesRegex(ValueError, "no external input 'drive.power'"):
            simulator.step({"drive.power": 1.0}, 0.05)
        # A value that is no number is a TypeError naming the input, not pybind11's bare
        # RuntimeError; a numpy number is a number.
        for bad in ("abc", None, [1.0]):
            with self.assertRaisesRegex(TypeError, "inputs: controller.power_command: expected a "
                                                   "number in the input's SI unit, got"):
                simulator.step({"controller.power_command": bad}, 0.05)
        with self.assertRaisesRegex(TypeError, "inputs: controller.power_command: expected"):
            simulator.step("abc", 0.05)
        with self.assertRaisesRegex(ValueError, "save: expected a record's file name, got ''"):
            simulator.save("")
        with self.assertRaisesRegex(ValueError, "the run is at t = 0.5 s"):
            simulator.advance_to(0.1)
        simulator.step({"controller.power_command": np.float32(2.0)}, 0.05)  # a numpy number
        with self.assertRaises(tcpmsim.ParameterError):
            simulator.set("muscle.mechanics.k2", -1.0)
        first = simulator.reset()
        again = simulator.reset()
        self.assertEqual(first["muscle/force"], again["muscle/force"])
        simulator.set("muscle.mechanics.k2", 3.0)
        simulator.reset()
        self.assertEqual(simulator.parameter("muscle.mechanics.k2"), 3.0)

    def test_save_writes_the_record_tcpmsim_run_writes(self):
        scenario = tcpmsim.Scenario.from_yaml(EXTERNAL, set={"scenario.duration": "2 s"})
        simulator = tcpmsim.Simulator(scenario)
        while not simulator.finished:
            simulator.step({"controller.power_command": 1.0}, 0.05)
        with tempfile.TemporaryDirectory() as directory:
            path = simulator.save(os.path.join(directory, "stepped.h5"))
            with h5py.File(path, "r") as record:
                self.assertEqual(record.attrs["status"], "complete")
                np.testing.assert_array_equal(record["controller/power_command"][1:],
                                              np.full(40, 1.0))


class ControlTaskTest(unittest.TestCase):
    def test_the_analysis_of_control_tasks_on_any_closed_run(self):
        """tcpmsim.control_task is `tcpmsim control-tasks`' analysis (without its calibration
        runs): the same rise times, Bode points, bandwidth and estimation errors, bit for bit."""
        sweep = "configs/ch7_control/force_sweep.yaml"
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "tasks.h5")
            subprocess.run([os.environ["TCPMSIM"], "control-tasks", FORCE_STEPS, sweep,
                            "--no-calibration", "-q", "-o", path], check=True)
            with h5py.File(path) as tasks:
                steps, swept = tasks["ch7_force_steps"], tasks["ch7_force_sweep"]
                task = tcpmsim.control_task(tcpmsim.Scenario.from_yaml(FORCE_STEPS).run())
                for key in ("step_time", "rise_time"):
                    np.testing.assert_array_equal(task["steps"][key], steps[key][:])
                self.assertEqual(task["steps"]["reached"], [bool(v) for v in steps["reached"]])
                errors = steps["estimation_error"][:]
                self.assertEqual(task["estimation_error"]["count"], len(errors))
                self.assertAlmostEqual(task["estimation_error"]["mean"], errors.mean(), places=15)
                task = tcpmsim.control_task(tcpmsim.Scenario.from_yaml(sweep).run())
                for key in ("frequency", "phase"):
                    np.testing.assert_array_equal(task["response"][key], swept[key][:])
                np.testing.assert_array_equal(task["response"]["magnitude_db"],
                                              swept["magnitude"][:])
                self.assertEqual(task["bandwidth"], swept["bandwidth"][0])
        # The thesis' force bandwidth, 0.056 Hz (section 7.4), from the same PI.
        self.assertAlmostEqual(task["bandwidth"], 0.056, delta=0.002)

    def test_tracking_error_and_refusals(self):
        result = tcpmsim.Scenario.from_yaml(FORCE_STEPS, set=SHORT).run()
        task = tcpmsim.control_task(result, estimate="")
        self.assertNotIn("estimation_error", task)
        time, force = result["time"], result["muscle/force"]
        after = time >= 40.0  # the first step
        error = force[after] - result["controller/reference"][after]
        self.assertEqual(task["tracking_error"]["count"], after.sum())
        self.assertAlmostEqual(task["tracking_error"]["rmse"], np.sqrt(np.mean(error ** 2)),
                               places=14)
        # The first step, 0.45 -> 0.375 N at 40 s: its overshoot is how far the force goes below
        # 0.375 N before the next step, over the reference's change.
        held = (time >= 40.0) & (time < 60.0)
        below = max(0.0, 0.375 - force[held].min()) / 0.075
        self.assertAlmostEqual(task["steps"]["overshoot"][0], below, places=12)
        self.assertGreater(below, 0.0)
        with self.assertRaisesRegex(tcpmsim.UsageError, "not a controller's reference signal"):
            tcpmsim.control_task(result, reference="muscle/force")
        with self.assertRaisesRegex(tcpmsim.UsageError, "not a scalar in the reference's unit"):
            tcpmsim.control_task(result, truth="muscle/temperature")


class EnvironmentTest(unittest.TestCase):
    def test_a_whole_task_within_bounds_and_a_seeded_reset_reproduces_it(self):
        def episode(env, seed):
            observation, info = env.reset(seed=seed)
            observations, rewards = [observation], []
            generator = np.random.default_rng(3)
            while True:
                self.assertTrue(env.observation_space.contains(observation), observation)
                action = generator.uniform(env.action_space.low, env.action_space.high)
                observation, reward, terminated, truncated, info = env.step(action)
                observations.append(observation)
                rewards.append(reward)
                self.assertFalse(terminated)
                if truncated:
                    return np.array(observations), np.array(rewards), info

        env = MuscleEnv(tcpmsim.Scenario.from_yaml(EXTERNAL, set=SHORT), target="force",
                        reference=lambda t: 0.45 if t < 30.0 else 0.5)
        self.assertEqual(env.action_space.shape, (1,))
        np.testing.assert_array_equal(env.action_space.low, [0.10])
        np.testing.assert_array_equal(env.action_space.high, [3.12])
        self.assertEqual(env.observation_space.shape, (3,))
        a_observations, a_rewards, info = episode(env, seed=11)
        self.assertEqual(info["time"], 60.0)
        self.assertTrue(np.all(np.isfinite(a_observations)))
        self.assertTrue(np.all(a_rewards <= 0.0))
        b_observations, b_rewards, _ = episode(env, seed=11)
        np.testing.assert_array_equal(a_observations, b_observations)
        np.testing.assert_array_equal(a_rewards, b_rewards)
        c_observations, _, _ = episode(env, seed=12)  # other measurement noise
        self.assertFalse(np.array_equal(a_observations, c_observations))

    def test_true_state_observation_and_clipped_actions(self):
        env = MuscleEnv(tcpmsim.Scenario.from_yaml(EXTERNAL, set={"scenario.duration": "5 s"}),
                        observe="state")
        observation, _ = env.reset()
        self.assertEqual(observation.shape, (6,))
        observation, _, _, _, info = env.step([10.0])  # above P_max: held at P_max
        self.assertEqual(info["power"], 3.12)
        self.assertTrue(env.observation_space.contains(observation))
        with self.assertRaisesRegex(ValueError, "target"):
            MuscleEnv(EXTERNAL, target="angle")

    def test_the_task_is_the_scenario_reference_unless_one_is_given(self):
        settings = {"scenario.duration": "45 s"}
        env = MuscleEnv(tcpmsim.Scenario.from_yaml(EXTERNAL, set=settings))
        observation, info = env.reset()
        self.assertAlmostEqual(observation[1], 0.45, places=12)  # the lead-in, mid-range
        while info["time"] < 41.0:
            observation, _, _, _, info = env.step([1.0])
        self.assertAlmostEqual(observation[1], 0.375, places=12)  # the first step, at 40 s
        self.assertEqual(info["reference"], observation[1])
        with self.assertRaisesRegex(ValueError, "is in m, but the scenario.s task .* is in N"):
            MuscleEnv(tcpmsim.Scenario.from_yaml(EXTERNAL, set=settings), target="deflection")
        with self.assertRaisesRegex(ValueError, "reports no task"):
            with open(EXTERNAL) as config:
                untasked = "".join(line for line in config
                                   if not line.startswith(("  target:", "  reference:")))
            MuscleEnv(tcpmsim.Scenario.from_yaml(untasked, set=settings))


if __name__ == "__main__":
    unittest.main()
