"""tcpmsim-plot's pictures, checked on the figures they draw (axes, labels, scales, legends,
colour bars), from records the program makes here in a temporary directory.

Run from the source root (TCPMSIM: the program, default build/tcpmsim):
    PYTHONPATH=build/python:tools /usr/bin/python3 -m unittest -v tests/python/test_plot_tool.py
"""

import contextlib
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(SOURCE, "tools"))

import h5py  # noqa: E402
import numpy as np  # noqa: E402

from tcpmsim_plot import common, steps, sweep, sweep_traces, traces  # noqa: E402
from tcpmsim_plot.bundle import bundle_figure  # noqa: E402
from tcpmsim_plot.common import PlotError, plt  # noqa: E402
from tcpmsim_plot.fit import fit_figure  # noqa: E402

PROGRAM = os.path.abspath(os.path.join(SOURCE, os.environ.get("TCPMSIM", "build/tcpmsim")))
PLOT = os.path.join(SOURCE, "tools", "tcpmsim-plot")
CONFIGS = os.path.join(SOURCE, "configs")
WORK = None  # the temporary directory of every test's files
MADE = {}


def setUpModule():
    global WORK
    WORK = tempfile.TemporaryDirectory(prefix="test_plot_tool_")


def tearDownModule():
    WORK.cleanup()


def path(name):
    return os.path.join(WORK.name, name)


def tcpmsim(*arguments):
    subprocess.run([PROGRAM, *arguments], check=True, cwd=SOURCE, stdout=subprocess.DEVNULL)


def record(name, config, *settings):
    """A run's record (made once for all the tests)."""
    if name not in MADE:
        arguments = ["run", os.path.join(CONFIGS, config), "-q", "-o", path(name)]
        for setting in settings:
            arguments += ["--set", setting]
        tcpmsim(*arguments)
        MADE[name] = path(name)
    return MADE[name]


def force_steps_record():
    return record("force_steps.h5", "ch7_control/force_steps.yaml", "scenario.duration=100 s")


def plot_tool(*arguments):
    """tools/tcpmsim-plot's exit code and stderr."""
    done = subprocess.run([PLOT, *arguments], capture_output=True, text=True, cwd=SOURCE)
    return done.returncode, done.stderr


def legend_texts(axis):
    legend = axis.get_legend()
    return [text.get_text() for text in legend.get_texts()] if legend else []


class FigureTest(unittest.TestCase):
    def keep(self, figure):
        self.addCleanup(plt.close, figure)
        return figure


class Steps(FigureTest):
    def test_open_loop_power_steps_two_axes_and_analyze_rise_times(self):
        power_steps = record("power_steps.h5", "analysis/power_steps.yaml")
        analysis = path("power_steps_analysis.h5")
        tcpmsim("analyze", power_steps, "--response", "muscle/force", "--reference", "drive/power",
                "-q", "-o", analysis)
        figure = self.keep(steps.steps_figure(power_steps, "drive/power", "muscle/force"))
        # W and N: two panels, each labelled with its unit, each holding its own line
        self.assertEqual(len(figure.axes), 2)
        reference_axis, response_axis = figure.axes
        self.assertIn("drive/power", reference_axis.get_ylabel())
        self.assertIn("[W]", reference_axis.get_ylabel())
        self.assertIn("muscle/force", response_axis.get_ylabel())
        self.assertIn("[N]", response_axis.get_ylabel())
        self.assertEqual([line.get_label() for line in reference_axis.get_lines()], ["drive/power"])
        self.assertIn("muscle/force", [line.get_label() for line in response_axis.get_lines()])
        # the marks are analyze's: rise and settling of each of the four steps
        with h5py.File(analysis, "r") as done:
            expected = {name: done[f"steps/{name}"][()] for name in
                        ("step_time", "start", "final_value", "rise_time", "settling_time")}
        drawn = figure.metrics
        self.assertEqual(len(drawn), 4)
        for name, values in expected.items():
            np.testing.assert_allclose([step[name] for step in drawn], values, rtol=1e-9, atol=1e-9,
                                       err_msg=name)
        self.assertNotIn("never rose", legend_texts(response_axis))
        annotations = [child.get_text() for child in response_axis.texts]
        self.assertEqual(annotations, ["16.7 s"] * 4)
        self.assertIn("median rise time 16.7 s", reference_axis.get_title())
        self.assertIn("median settling time 29.7 s", reference_axis.get_title())
        # the crossings drawn lie at 10 % and 90 % of y_f - y0
        crossings = [line for line in response_axis.get_lines() if line.get_marker() == "o"]
        self.assertEqual(len(crossings), 4)
        for line, step in zip(crossings, drawn):
            np.testing.assert_allclose(line.get_xdata(), [step["lower_time"], step["upper_time"]])
            size = step["final_value"] - step["start"]
            np.testing.assert_allclose(line.get_ydata(),
                                       [step["start"] + 0.1 * size, step["start"] + 0.9 * size],
                                       atol=2e-5)

    def test_closed_loop_one_axis_and_temperature_in_degC(self):
        force_steps = force_steps_record()
        figure = self.keep(steps.steps_figure(force_steps, "controller/reference", "load/force"))
        self.assertEqual(len(figure.axes), 1)  # N and N share the axis
        self.assertIn("[N]", figure.axes[0].get_ylabel())
        self.assertEqual(len(figure.metrics), 3)
        # a temperature's response is drawn in degC
        figure = self.keep(steps.steps_figure(force_steps, "controller/reference",
                                              "muscle/temperature"))
        response_axis = figure.axes[1]
        self.assertIn("[degC]", response_axis.get_ylabel())
        with h5py.File(force_steps, "r") as done:
            kelvin = done["muscle/temperature"][()]
        line = next(l for l in response_axis.get_lines() if l.get_label() == "muscle/temperature")
        np.testing.assert_allclose(line.get_ydata(), kelvin - 273.15)

    def test_to_reference_gives_the_control_tasks_rise_times(self):
        try:
            import tcpmsim as module  # build/python
        except ImportError:
            self.skipTest("the tcpmsim module is not on PYTHONPATH (build/python)")
        force_steps = force_steps_record()
        figure = self.keep(steps.steps_figure(force_steps, "controller/reference", "load/force",
                                              to_reference=True))
        result = module.Scenario.from_yaml(os.path.join(CONFIGS, "ch7_control/force_steps.yaml"),
                                           set={"scenario.duration": "100 s"}).run()
        task = module.control_task(result, truth="load/force", estimate="")["steps"]
        drawn = figure.metrics
        np.testing.assert_allclose([step["step_time"] for step in drawn], task["step_time"])
        for step, rise, reached in zip(drawn, task["rise_time"], task["reached"]):
            if reached:
                self.assertAlmostEqual(step["rise_time"], rise, places=9)
            else:
                self.assertTrue(np.isnan(step["rise_time"]))
        self.assertFalse(all(task["reached"]))  # the 60 s step is not reached within its hold
        self.assertIn("never rose", legend_texts(figure.axes[0]))
        self.assertIn("to the reference", figure.axes[0].get_title())
        with self.assertRaisesRegex(PlotError, "do not share a unit"):
            steps.steps_figure(force_steps, "controller/reference", "muscle/temperature",
                               to_reference=True)

    def test_a_flat_response_never_rose(self):
        flat = path("flat.h5")
        time = np.arange(0.0, 20.0, 0.5)
        with h5py.File(flat, "w") as made:  # power steps at 5 s and 15 s; the force only at 15 s
            power = np.select([time < 5.0, time < 15.0], [0.0, 1.0], 2.0)
            for name, values, unit in [("time", time, "s"), ("drive/power", power, "W"),
                                       ("muscle/force", np.where(time < 15.0, 0.1, 0.2), "N")]:
                made[name] = values
                made[name].attrs["units"] = unit
        figure = self.keep(steps.steps_figure(flat, "drive/power", "muscle/force"))
        rise = [step["rise_time"] for step in figure.metrics]
        self.assertTrue(np.isnan(rise[0]))  # the force does not move after the 5 s step
        self.assertEqual(rise[1], 0.0)  # it jumps with the 15 s step
        self.assertIn("never rose", legend_texts(figure.axes[1]))


class Traces(FigureTest):
    def test_pair_record_default_channels(self):
        pair = record("pair.h5", "pair/angle_steps.yaml", "scenario.duration=30 s")
        figure = self.keep(traces.traces_figure(pair))
        axes = figure.axes
        self.assertEqual([axis.get_ylabel() for axis in axes],
                         ["power\n[W]", "temperature\n[degC]", "force\n[N]", "angle\n[rad]"])
        self.assertEqual(legend_texts(axes[0]), ["left_drive/power", "right_drive/power"])
        self.assertEqual(legend_texts(axes[1]), ["left/temperature", "right/temperature"])
        self.assertEqual(legend_texts(axes[2]), ["left/force", "right/force"])
        self.assertEqual(legend_texts(axes[3]), ["load/angle", "controller/reference"])
        temperature = axes[1].get_lines()[0].get_ydata()
        self.assertAlmostEqual(temperature[0], 23.0, places=6)  # the ambient, in degC
        self.assertEqual(axes[-1].get_xlabel(), "time [s]")
        # and the command line draws it without --channels
        code, error = plot_tool("traces", pair, "-o", path("pair.png"))
        self.assertEqual(code, 0, error)
        self.assertGreater(os.path.getsize(path("pair.png")), 0)

    def test_single_muscle_keeps_its_channels(self):
        single = record("identification.h5", "ch7_identification.yaml", "scenario.duration=20 s")
        figure = self.keep(traces.traces_figure(single))
        self.assertEqual([axis.get_ylabel() for axis in figure.axes],
                         ["drive/power\n[W]", "muscle/temperature\n[degC]",
                          "muscle/deflection\n[mm]", "muscle/force\n[N]"])

    def test_nine_panels_title_clear_of_the_first(self):
        pair = record("pair.h5", "pair/angle_steps.yaml", "scenario.duration=30 s")
        channels = ["left/force", "right/force", "left/temperature", "right/temperature",
                    "left_drive/power", "right_drive/power", "load/angle", "controller/reference",
                    "load/stiffness"]
        figure = self.keep(traces.traces_figure(pair, channels))
        figure.savefig(path("nine.png"))  # lays the figure out as saving does
        self.assertEqual(len(figure.axes), 9)
        for axis, channel in zip(figure.axes, channels):
            self.assertTrue(axis.get_ylabel().startswith(channel + "\n["), axis.get_ylabel())
        renderer = figure.canvas.get_renderer()
        title = figure._suptitle.get_window_extent(renderer)
        first = figure.axes[0].get_tightbbox(renderer)
        self.assertGreaterEqual(title.y0, first.y1 - 0.5)
        for upper, lower in zip(figure.axes, figure.axes[1:]):  # no panel over the next
            self.assertGreaterEqual(upper.get_position().y0, lower.get_position().y1)

    def test_missing_channel_is_named(self):
        single = record("identification.h5", "ch7_identification.yaml", "scenario.duration=20 s")
        with contextlib.redirect_stderr(io.StringIO()) as warning:
            with self.assertRaisesRegex(PlotError, "none of the channels muscle/colour is in"):
                traces.traces_figure(single, ["muscle/colour"])
        self.assertIn("skipped: muscle/colour", warning.getvalue())


SWEEP = """sweep: {name: plot_test, seed: 1}
scenario: %s
axes:
  - parameter: muscle.thermal.conductance
    range: {from: 10 mW/K, to: 160 mW/K, count: 3, spacing: log}
  - parameter: muscle.thermal.heat_capacity
    values: [0.275 J/K, 0.55 J/K, 1.1 J/K]
metrics:
  - {name: time_constant, type: time_constant, channel: muscle/temperature, from: 10 s}
  - {name: final_temperature, type: final_value, channel: muscle/temperature}
store: {traces: decimated, interval: 10 s}
"""


def sweep_file(*settings):
    """A 3 x 3 sweep of the thermal step (log-spaced hA over more than a decade, three C), with
    its traces stored; made once per settings."""
    key = ("sweep",) + settings
    if key not in MADE:
        name = "sweep%d.h5" % sum(1 for made in MADE if isinstance(made, tuple))
        spec = path("sweep.yaml")
        with open(spec, "w", encoding="utf-8") as file:
            file.write(SWEEP % os.path.join(CONFIGS, "sweeps", "thermal_step.yaml"))
        arguments = ["sweep", spec, "--jobs", "1", "-q", "-o", path(name)]
        for setting in settings:
            arguments += ["--set", setting]
        tcpmsim(*arguments)
        MADE[key] = path(name)
    return MADE[key]


class Sweep(FigureTest):
    def test_few_colour_values_get_a_legend_and_log_axes(self):
        figure = self.keep(sweep.sweep_figure(sweep_file(), "muscle.thermal.conductance", None,
                                              "time_constant", "muscle.thermal.heat_capacity"))
        self.assertEqual(len(figure.axes), 1)  # no colour bar
        axis = figure.axes[0]
        self.assertEqual(legend_texts(axis), ["0.275 J/K", "0.55 J/K", "1.1 J/K"])
        self.assertEqual(axis.get_legend().get_title().get_text(), "muscle.thermal.heat_capacity")
        self.assertEqual(axis.get_xscale(), "log")  # 10 to 160 mW/K
        self.assertEqual(axis.get_yscale(), "log")  # tau from 1.7 s to 110 s
        self.assertEqual(axis.get_xlabel(), "muscle.thermal.conductance [W/K]")
        self.assertEqual(axis.get_ylabel(), "time_constant [s]")

    def test_many_colour_values_get_a_colour_bar_and_temperatures_degC(self):
        figure = self.keep(sweep.sweep_figure(sweep_file(), "muscle.thermal.heat_capacity", None,
                                              "final_temperature", "time_constant"))
        self.assertEqual(len(figure.axes), 2)  # nine values: a colour bar
        self.assertEqual(figure.axes[1].get_ylabel(), "time_constant [s]")
        axis = figure.axes[0]
        self.assertEqual(axis.get_ylabel(), "final_temperature [degC]")
        self.assertEqual(axis.get_xscale(), "log")  # 0.275, 0.55, 1.1: log-spaced
        self.assertEqual(axis.get_yscale(), "linear")  # 26 to 72 degC
        values = axis.collections[0].get_offsets()[:, 1]
        self.assertTrue(np.all((values > 23.0) & (values < 75.0)), values)
        # a grid: the heat map, its colour bar labelled in degC
        figure = self.keep(sweep.sweep_figure(sweep_file(), "muscle.thermal.conductance",
                                              "muscle.thermal.heat_capacity", "final_temperature"))
        self.assertEqual(figure.axes[1].get_ylabel(), "final_temperature [degC]")

    def test_which_axes_are_logarithmic(self):
        self.assertTrue(sweep.logarithmic(np.repeat(np.geomspace(0.029, 0.116, 4), 4)))
        self.assertTrue(sweep.logarithmic([1.0, 100.0]))
        self.assertFalse(sweep.logarithmic([1.0, 2.0, 3.0, 4.0]))
        self.assertFalse(sweep.logarithmic([-1.0, 10.0, 100.0]))
        self.assertFalse(sweep.logarithmic([2.0, 4.0]))
        types = {"final_temperature": "final_value", "temperature_error": "rmse"}
        self.assertTrue(common.is_absolute_temperature("final_temperature", "K", types))
        self.assertFalse(common.is_absolute_temperature("temperature_error", "K", types))
        self.assertTrue(common.is_absolute_temperature("muscle.thermal.ambient_temperature", "K",
                                                       {}))


class SweepTraces(FigureTest):
    def test_every_stored_run_labelled_by_its_parameters(self):
        stored = sweep_file()
        figure = self.keep(sweep_traces.sweep_traces_figure(stored, "muscle/temperature"))
        axis = figure.axes[0]
        self.assertEqual(len(axis.get_lines()), 9)
        labels = legend_texts(axis)
        self.assertEqual(len(labels), 9)
        self.assertEqual(labels[0], "run 0: conductance = 0.01 W/K, heat_capacity = 0.275 J/K")
        self.assertEqual(labels[8], "run 8: conductance = 0.16 W/K, heat_capacity = 1.1 J/K")
        self.assertEqual(axis.get_ylabel(), "muscle/temperature [degC]")
        self.assertEqual(axis.get_xlabel(), "time [s]")
        with h5py.File(stored, "r") as done:
            kelvin = done["runs/4/scenario/muscle/temperature"][()]
        np.testing.assert_allclose(axis.get_lines()[4].get_ydata(), kelvin - 273.15)
        some = self.keep(sweep_traces.sweep_traces_figure(stored, "drive/power", runs=[0, 8]))
        self.assertEqual(len(some.axes[0].get_lines()), 2)
        self.assertEqual(some.axes[0].get_ylabel(), "drive/power [W]")

    def test_command_line_and_what_is_missing(self):
        code, error = plot_tool("sweep-traces", sweep_file(), "--channel", "muscle/temperature",
                                "--scenario", "scenario", "-o", path("sweep_traces.png"))
        self.assertEqual(code, 0, error)
        self.assertGreater(os.path.getsize(path("sweep_traces.png")), 0)
        with self.assertRaisesRegex(PlotError, "no stored run records 'muscle/colour'"):
            sweep_traces.sweep_traces_figure(sweep_file(), "muscle/colour")
        with self.assertRaisesRegex(PlotError, "stores no scenario 'loop'"):
            sweep_traces.sweep_traces_figure(sweep_file(), "muscle/temperature", "loop")
        with self.assertRaisesRegex(PlotError, "holds no traces"):
            sweep_traces.sweep_traces_figure(sweep_file("store={traces: none}"),
                                             "muscle/temperature")


class Fit(FigureTest):
    @classmethod
    def setUpClass(cls):
        cls.directory = path("fit")
        if os.path.isdir(cls.directory):
            return
        protocol = record("protocol.h5", "discover/ch7_protocol.yaml", "scenario.duration=60 s")
        spec = path("fit.yaml")
        with open(spec, "w", encoding="utf-8") as file:
            file.write(f"""model: {os.path.join(CONFIGS, "discover", "ch7_base.yaml")}
outputs:
  - {{channel: force, output: load.force, noise: 1 mN}}
parameters:
  - {{path: muscle.thermal_force.kappa_P, bounds: [1 mN/J, 50 mN/J]}}
  - {{path: muscle.thermal_force.kappa_c, bounds: [0.01 1/s, 1 1/s]}}
identification: [0 s, 40 s]
validation: [40 s, 60 s]
multistart: {{starts: 2, refine: 1, seed: 1}}
""")
        tcpmsim("fit", spec, "--data", protocol, "--out", cls.directory, "-q", "--jobs", "1")

    def test_measured_fitted_windows_and_residual(self):
        figure = self.keep(fit_figure(self.directory))
        self.assertEqual(len(figure.axes), 2)
        top, bottom = figure.axes
        self.assertEqual(top.get_ylabel(), "force\n[N]")
        self.assertEqual(bottom.get_ylabel(), "residual\n[N]")
        self.assertEqual(bottom.get_xlabel(), "time [s]")
        self.assertEqual(legend_texts(top), ["measured", "initial model", "fitted model",
                                             "identification window", "validation window"])
        for axis in (top, bottom):  # the windows shaded: [0 s, 40 s] and [40 s, 60 s]
            spans = sorted((patch.get_xy()[:, 0].min(), patch.get_xy()[:, 0].max())
                           for patch in axis.patches)
            np.testing.assert_allclose(spans, [[0.0, 40.0], [40.0, 60.0]], atol=1e-9)
        with h5py.File(os.path.join(self.directory, "fit.h5"), "r") as done:
            residual = done["measured/force"][()] - done["fitted/force"][()]
        line = next(l for l in bottom.get_lines() if l.get_label() == "measured - fitted")
        np.testing.assert_allclose(line.get_ydata(), residual)
        with open(os.path.join(self.directory, "fit.json"), encoding="utf-8") as file:
            summary = json.load(file)
        rmse = summary["identification"]["force"]["rmse"]
        self.assertIn(f"identification RMSE {rmse:.3g} N", top.get_title())
        self.assertIn("validation RMSE", top.get_title())
        self.assertIn("kappa_P = ", figure._suptitle.get_text())

    def test_command_line_writes_beside_the_fit(self):
        code, error = plot_tool("fit", self.directory)
        self.assertEqual(code, 0, error)
        self.assertGreater(os.path.getsize(os.path.join(self.directory, "fit.png")), 0)
        code, error = plot_tool("fit", WORK.name, "-o", path("none.png"))
        self.assertEqual(code, 1)
        self.assertIn("is no tcpmsim fit --out directory", error)


class Temperatures(FigureTest):
    def test_differences_are_not_offset(self):
        values, unit = common.display_difference(np.array([0.5, -1.0]), "K")
        self.assertEqual(unit, "degC")
        np.testing.assert_array_equal(values, [0.5, -1.0])
        values, unit = common.display(np.array([273.15]), "K")
        self.assertEqual((unit, values[0]), ("degC", 0.0))

    def test_bundle_in_degC(self):
        bundle = record("bundle.h5", "bundle/hexagonal_parallel.yaml", "scenario.duration=20 s")
        figure = self.keep(bundle_figure(bundle, "bundle"))
        section, members = figure.axes
        self.assertIn("[degC]", section.get_title())
        self.assertEqual(members.get_ylabel(), "temperature [degC]")
        with h5py.File(bundle, "r") as done:
            kelvin = done["bundle/temperature"][:, 0]
        np.testing.assert_allclose(members.get_lines()[0].get_ydata(), kelvin - 273.15)


if __name__ == "__main__":
    unittest.main()
