"""The Python module against the command line: the same config gives the same samples, bit for
bit, and the same bad input the same message.

Run by ctest with PYTHONPATH=<build>/python:tests/python, TCPMSIM=<the program> and the source
tree as the working directory."""

import os
import subprocess
import tempfile
import unittest
import warnings

import h5py
import numpy as np

import record_compare
import tcpmsim

PROGRAM = os.environ["TCPMSIM"]
# A single muscle under the identification protocol, a bundle (member sets: 2-D channels), an
# antagonistic pair under angle control with self-sensing, a coil spring.
CONFIGS = ["configs/ch7_identification.yaml", "configs/bundle/hexagonal_parallel.yaml",
           "configs/pair/angle_steps.yaml", "configs/ch4/st_harmonic_first.yaml"]


def command_line_run(config, output, *settings):
    arguments = [PROGRAM, "run", config, "-q", "-o", output]
    for setting in settings:
        arguments += ["--set", setting]
    subprocess.run(arguments, check=True)


def command_line_error(*arguments):
    """The message `tcpmsim` prints for a bad input (its last stderr line), which must fail."""
    done = subprocess.run([PROGRAM, *arguments], capture_output=True, text=True)
    assert done.returncode != 0, arguments
    return done.stderr.strip().splitlines()[-1]


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


class PythonRunsAreCommandLineRuns(unittest.TestCase):
    def setUp(self):
        self.directory = tempfile.TemporaryDirectory()
        self.addCleanup(self.directory.cleanup)

    def path(self, name):
        return os.path.join(self.directory.name, name)

    def test_every_channel_is_bit_identical_to_tcpmsim_run(self):
        for config in CONFIGS:
            with self.subTest(config=config):
                command_line_run(config, self.path("cli.h5"))
                result = tcpmsim.Scenario.from_yaml(config).run()
                with h5py.File(self.path("cli.h5"), "r") as record:
                    self.assertTrue(same_bits(record["time"][()], result["time"]))
                    for channel in result.channels[1:]:
                        self.assertTrue(same_bits(record[channel][()], result[channel]), channel)
                        self.assertEqual(record[channel].attrs["units"], result.units[channel])
                    self.assertEqual(record.attrs["config"], result.config)
                    self.assertEqual(record.attrs["solver_steps"], result.statistics["steps"])

    def test_save_writes_the_record_tcpmsim_run_writes(self):
        for config in CONFIGS[:2]:
            with self.subTest(config=config):
                command_line_run(config, self.path("cli.h5"))
                result = tcpmsim.Scenario.from_yaml(config).run()
                self.assertEqual(result.save(self.path("python.h5")), self.path("python.h5"))
                # Bit for bit, but for the command line each was made by.
                self.assertEqual(record_compare.differences(
                    self.path("cli.h5"), self.path("python.h5"), ignore=["/@command_line"]), [])
                with h5py.File(self.path("cli.h5"), "r") as cli, \
                        h5py.File(self.path("python.h5"), "r") as python:
                    self.assertIn(" run " + config, cli.attrs["command_line"])
                    self.assertTrue(python.attrs["command_line"].startswith("python3 "))

    def test_set_is_the_command_lines_set(self):
        settings = {"muscle.mechanics.k2": "3 mN/mm", "muscle.thermal_force.kappa_c": "0.2 1/s"}
        command_line_run(CONFIGS[0], self.path("cli.h5"),
                         *(f"{path}={value}" for path, value in settings.items()))
        scenario = tcpmsim.Scenario.from_yaml(CONFIGS[0])
        for path, value in settings.items():
            scenario.set(path, value)
        self.assertEqual(scenario.parameters["muscle.mechanics.k2"], 3.0)  # SI: N/m
        result = scenario.run()
        with h5py.File(self.path("cli.h5"), "r") as record:
            for channel in result.channels[1:]:
                self.assertTrue(same_bits(record[channel][()], result[channel]), channel)

    def test_an_implausible_value_warns_with_its_range_and_strict_filters_raise(self):
        # Issue 30: k1 in N/mm where mN/mm was meant is 1000 times its typical range.
        scenario = tcpmsim.Scenario.from_yaml(CONFIGS[0])
        self.assertEqual(scenario.warnings, [])
        with self.assertWarnsRegex(UserWarning, r"muscle.mechanics.k1: '14.04 N/mm' is 14040 N/m"):
            scenario.set("muscle.mechanics.k1", "14.04 N/mm")
        self.assertEqual(len(scenario.warnings), 1)
        self.assertIn("1/1000 of it, 14.04 N/m, would be typical", scenario.warnings[0])
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # as --strict
            with self.assertRaises(UserWarning):
                tcpmsim.Scenario.from_yaml(CONFIGS[0]).set("muscle.mechanics.k1", "14.04 N/mm")

    def test_a_plain_number_set_on_a_parameter_is_si(self):
        # As Scenario.parameters and the Simulator give it: 3.0 for k2 is 3 N/m (= 3 mN/mm),
        # the same run bit for bit; a dimensionless parameter and a count stay plain numbers.
        with_unit = tcpmsim.Scenario.from_yaml(CONFIGS[0]).set("muscle.mechanics.k2", "3 mN/mm")
        plain = tcpmsim.Scenario.from_yaml(CONFIGS[0]).set("muscle.mechanics.k2", 3.0)
        self.assertEqual(plain.parameters["muscle.mechanics.k2"], 3.0)
        self.assertEqual(plain.overrides, ["muscle.mechanics.k2=3.0 N/m"])
        self.assertTrue(same_bits(plain.run(duration=20)["muscle/force"],
                                  with_unit.run(duration=20)["muscle/force"]))
        # A negative SI value is refused as the command line refuses it, with the unit shown.
        with self.assertRaisesRegex(tcpmsim.ConfigError, "got '-3.0 N/m'"):
            plain.set("muscle.mechanics.k2", -3.0)
        # Located at the call that set it, not at a command line (issue 30).
        with self.assertRaisesRegex(tcpmsim.ConfigError,
                                    r"^tcpmsim\.Scenario \(set muscle\.mechanics\.k2=-3\.0 N/m\): "
                                    r"error: muscle\.mechanics\.k2"):
            plain.set("muscle.mechanics.k2", -3.0)
        # A path that is not a model parameter keeps the number as it is.
        self.assertEqual(tcpmsim.Scenario.from_yaml(CONFIGS[0]).set("scenario.seed", 5).overrides,
                         ["scenario.seed=5"])

    def test_yaml_text_runs_as_its_file_does(self):
        with open(CONFIGS[0]) as file:
            text = file.read()
        from_text = tcpmsim.Scenario.from_yaml(text).run()
        from_file = tcpmsim.Scenario.from_yaml(CONFIGS[0]).run()
        self.assertTrue(same_bits(from_text["muscle/force"], from_file["muscle/force"]))

    def test_settings_from_the_start_are_the_command_lines_set(self):
        # A scenario that cannot be built without a value (a measurement to replay) takes it at
        # once; a bad one raises the --set message.
        inputs = self.path("inputs.h5")
        tcpmsim.Scenario.from_yaml("configs/discover/ch7_protocol.yaml").run(duration=20).save(inputs)
        command_line_run("configs/discover/ch7_base.yaml", self.path("cli.h5"),
                         f"measurement.file={inputs}", "scenario.duration=20 s")
        result = tcpmsim.Scenario.from_yaml(
            "configs/discover/ch7_base.yaml",
            set={"measurement.file": inputs, "scenario.duration": "20 s"}).run()
        with h5py.File(self.path("cli.h5"), "r") as record:
            self.assertTrue(same_bits(record["load/force"][()], result["load/force"]))
        with self.assertRaises(tcpmsim.ConfigError) as raised:
            tcpmsim.Scenario.from_yaml("configs/discover/ch7_base.yaml")
        self.assertIn("measurement.file", str(raised.exception))

    def test_runs_on_threads_equal_runs_one_at_a_time(self):
        base = tcpmsim.Scenario.from_yaml(CONFIGS[0])
        values = ["2 mN/mm", "3 mN/mm", "4 mN/mm", "5 mN/mm"]
        on_threads = tcpmsim.sweep(base, "muscle.mechanics.k2", values, jobs=2)
        for value, threaded in zip(values, on_threads):
            alone = base.copy().set("muscle.mechanics.k2", value).run()
            self.assertTrue(same_bits(threaded["muscle/force"], alone["muscle/force"]), value)
        self.assertEqual(base.overrides, [])  # sweep set copies, not the base
        # Stiffer muscles hold more force against the same deflection.
        peaks = [result["muscle/force"].max() for result in on_threads]
        self.assertEqual(peaks, sorted(peaks))

    def test_duration_and_output_rate_override_the_files(self):
        result = tcpmsim.Scenario.from_yaml(CONFIGS[0]).run(duration=10, output_rate="4 Hz")
        self.assertEqual(len(result["time"]), 41)
        self.assertEqual(result["time"][-1], 10.0)
        np.testing.assert_allclose(np.diff(result["time"]), 0.25, rtol=1e-12)
        self.assertIn("duration: 10 s", result.config)

    def test_arrays_are_read_only_views_that_outlive_their_result(self):
        result = tcpmsim.Scenario.from_yaml(CONFIGS[1]).run(duration=2)
        temperature = result["bundle/temperature"]
        self.assertEqual(temperature.shape, (len(result["time"]), len(result.members["bundle/temperature"])))
        expected = temperature.copy()
        del result
        self.assertTrue(same_bits(temperature, expected))
        with self.assertRaises(ValueError):
            temperature[0, 0] = 0.0
        with self.assertRaises(KeyError):
            tcpmsim.Scenario.from_yaml(CONFIGS[0]).run(duration=1)["muscle/forse"]


class PythonAnalysisIsTheCommandLines(unittest.TestCase):
    def test_analyze_on_a_result_gives_tcpmsim_analyze_on_its_record(self):
        with tempfile.TemporaryDirectory() as directory:
            record, analysis = (os.path.join(directory, name) for name in ("r.h5", "a.h5"))
            config = "configs/analysis/power_multisine.yaml"
            command_line_run(config, record)
            subprocess.run([PROGRAM, "analyze", record, "--response", "load/force", "--from",
                            "100", "-q", "-o", analysis], check=True)
            result = tcpmsim.Scenario.from_yaml(config).run()
            estimate = tcpmsim.analyze(result, "load/force", start=100)
            power = estimate["responses"]["drive/power"]
            self.assertEqual(estimate["method"], "lines")
            self.assertEqual(power["unit"], "N/W")
            with h5py.File(analysis, "r") as file:
                group = file["frequency_response/drive.power"]
                self.assertTrue(same_bits(group["frequency"][()], power["frequency"]))
                self.assertTrue(same_bits(group["real"][()], power["response"].real.copy()))
                self.assertTrue(same_bits(group["radius_95"][()], power["radius_95"]))
                self.assertEqual(group["bandwidth"][()], power["bandwidth"])
                self.assertEqual(file.attrs["command_line"].split()[1], "analyze")
            # From the record file too.
            again = tcpmsim.analyze(record, "load/force", start=100)
            self.assertTrue(same_bits(again["responses"]["drive/power"]["response"],
                                      power["response"]))

    def test_step_metrics_and_bad_requests(self):
        result = tcpmsim.Scenario.from_yaml("configs/analysis/power_steps.yaml").run()
        steps = tcpmsim.analyze(result, "muscle/force", reference="drive/power")["steps"]
        np.testing.assert_allclose(steps["rise_time"], np.log(9) / 0.1316, atol=0.01)
        with self.assertRaises(ValueError) as raised:
            tcpmsim.analyze(result, "muscle/forse")
        self.assertIn("muscle/force", str(raised.exception))


class PythonErrorsAreCommandLineErrors(unittest.TestCase):
    def test_bad_sources_and_arguments_raise_the_modules_errors(self):
        # Issue 31: a bare RuntimeError, bytes taken for a path, a cryptic ValueError.
        with self.assertRaises(tcpmsim.UsageError) as raised:
            tcpmsim.analyze(123, "muscle/force")
        self.assertIn("expected a Result or a record's path", str(raised.exception))
        with self.assertRaises(tcpmsim.ConfigError) as raised:
            tcpmsim.analyze("missing.h5", "muscle/force")
        self.assertEqual(str(raised.exception), "missing.h5: error: no such file")
        with open(CONFIGS[0], "rb") as file:
            text = file.read()
        self.assertEqual(tcpmsim.Scenario.from_yaml(text).name,
                         tcpmsim.Scenario.from_yaml(CONFIGS[0]).name)
        with self.assertRaises(TypeError) as raised:
            tcpmsim.Scenario.from_yaml(CONFIGS[0], set=["muscle.mechanics.k2=3 mN/mm"])
        self.assertIn("set: expected a dict of path: value", str(raised.exception))
        # A window that is no number is a TypeError naming it, not pybind11's RuntimeError.
        result = tcpmsim.Scenario.from_yaml("configs/analysis/power_steps.yaml").run()
        for name, value in (("start", "5 s"), ("end", [1]), ("segment", "x")):
            with self.assertRaisesRegex(TypeError, f"analyze: {name}: expected a number, got"):
                tcpmsim.analyze(result, "muscle/force", **{name: value})

    def test_a_bad_set_raises_the_command_lines_message(self):
        for setting, error in [("muscle.mechanics.k2=3 kg", tcpmsim.ConfigError),
                               ("muscle.mechanics.k2=-1 N/m", tcpmsim.ConfigError),
                               ("muscle.mechanics.k3=1 N/m", tcpmsim.ConfigError)]:
            with self.subTest(setting=setting):
                expected = command_line_error("validate", CONFIGS[0], "--set", setting)
                scenario = tcpmsim.Scenario.from_yaml(CONFIGS[0])
                path, value = setting.split("=")
                with self.assertRaises(error) as raised:
                    scenario.set(path, value)
                # The command line's message, located at the Python call instead of a --set
                # (issue 30).
                message = str(raised.exception)
                self.assertTrue(message.startswith("tcpmsim.Scenario (set %s): error: " % setting),
                                message)
                self.assertTrue(expected.endswith(message.split(": error: ", 1)[1]),
                                (expected, message))
                self.assertEqual(scenario.overrides, [])  # unchanged after the error
                self.assertTrue(isinstance(raised.exception, ValueError))

    def test_a_bad_file_raises_its_location(self):
        with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as file:
            with open(CONFIGS[0]) as source:
                file.write(source.read().replace("duration: 400 s", "duration: 400 kg"))
        self.addCleanup(os.unlink, file.name)
        expected = command_line_error("validate", file.name)
        with self.assertRaises(tcpmsim.ConfigError) as raised:
            tcpmsim.Scenario.from_yaml(file.name)
        self.assertEqual(str(raised.exception), expected)
        self.assertIn(f"{file.name}:9:", str(raised.exception))
        with self.assertRaises(tcpmsim.ConfigError):
            tcpmsim.Scenario.from_yaml("configs/no_such_file.yaml")

    def test_a_run_too_large_for_memory_raises_the_record_size_message(self):
        # Issue 31: the in-memory run grew until MemoryError; it is refused before it starts,
        # with the message `tcpmsim run` gives for the same record.
        scenario = tcpmsim.Scenario.from_yaml(CONFIGS[0])
        for keyword, setting in [("output_rate", "output.rate=1e9 Hz"),
                                 ("duration", "scenario.duration=1e9 s")]:
            with self.subTest(keyword=keyword):
                expected = command_line_error("run", CONFIGS[0], "--set", setting)
                with self.assertRaises(tcpmsim.ConfigError) as raised:
                    scenario.run(**{keyword: 1e9})
                message = str(raised.exception)
                # The same error; only the --set's spelling of 1e9 differs in its location.
                self.assertEqual(message.split(": error: ")[1], expected.split(": error: ")[1])
                self.assertIn("error: output.rate: the record would hold", message)
                self.assertIn("over the limit of 2 GB", message)
        with self.assertRaises(tcpmsim.ConfigError):
            tcpmsim.run_many([scenario.copy().set("output.rate", "1e9 Hz")])
        small = scenario.run(duration=10, max_output_size=1e9)
        self.assertEqual(small["time"][-1], 10.0)
        # A limit no run could meet is the argument's error, not the file's output.rate.
        for limit in (float("nan"), -1.0, 0.0):
            with self.assertRaisesRegex(tcpmsim.UsageError, "run: max_output_size: expected a "
                                                            "positive number of bytes"):
                scenario.run(duration=10, max_output_size=limit)

    def test_a_solver_failure_raises_with_the_samples_before_it(self):
        scenario = tcpmsim.Scenario.from_yaml(CONFIGS[0]).set("solver.max_steps", 200)
        with self.assertRaises(tcpmsim.SolverFailure) as raised:
            scenario.run()
        self.assertIn("more than 200 solver steps", str(raised.exception))
        partial = raised.exception.result
        self.assertEqual(partial.status, "failed")
        self.assertLess(partial["time"][-1], 400.0)
        unchecked = scenario.run(check=False)
        self.assertFalse(unchecked.succeeded)
        self.assertTrue(same_bits(unchecked["muscle/force"], partial["muscle/force"]))


if __name__ == "__main__":
    unittest.main()
