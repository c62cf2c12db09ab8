"""tcpmsim.Simulator and tcpmsim.env.MuscleEnv: a controller written in Python closes the loop.

Run by ctest with PYTHONPATH=<build>/python:tests/python, TCPMSIM=<the program> and the source
tree as the working directory."""

import math
import os
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
        # The reference the PID follows: the step sequence as its record holds it, at the
        # sample instants (the same signal, read where the PID reads it).
        reference = dict(zip(builtin["time"], builtin["controller/reference"]))
        state = {"integral": 0.0}
        outputs = simulator.outputs()
        while not simulator.finished:
            r = reference[simulator.time]
            power = pid_power(r, outputs["estimator/force"], state)
            outputs = simulator.step({"controller.power_command": power}, 0.05)
        stepped = simulator.result()
        self.assertEqual(stepped.status, "complete")
        for channel in ("muscle/force", "muscle/temperature", "drive/power",
                        "drive/inductance_measure", "estimator/force",
                        "controller/power_command"):
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
        with self.assertRaisesRegex(ValueError, "the run is at t = 0.5 s"):
            simulator.advance_to(0.1)
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


if __name__ == "__main__":
    unittest.main()
