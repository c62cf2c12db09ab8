"""The tcpmsim-plot command line: one sub-command per kind of picture."""
import argparse

from tcpmsim_plot import __doc__ as overview
from tcpmsim_plot.bode import plot_bode
from tcpmsim_plot.bundle import plot_bundle
from tcpmsim_plot.common import PlotError, fail
from tcpmsim_plot.discovery import plot_discovery
from tcpmsim_plot.fit import plot_fit
from tcpmsim_plot.steps import plot_steps
from tcpmsim_plot.sweep import plot_sweep
from tcpmsim_plot.sweep_traces import plot_sweep_traces
from tcpmsim_plot.traces import plot_traces


def output_of(arguments, suffix):
    return arguments.output or arguments.file.rsplit(".", 1)[0] + suffix


def parser():
    top = argparse.ArgumentParser(prog="tcpmsim-plot", description=overview,
                                  formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = top.add_subparsers(dest="command", required=True)

    def command(name, help_text, file_help):
        sub = commands.add_parser(name, help=help_text, description=help_text)
        sub.add_argument("file", help=file_help)
        sub.add_argument("-o", "--output", help="PNG or SVG to write (default: beside the file)")
        return sub

    traces = command("traces", "time traces of a record", "a tcpmsim run's record")
    traces.add_argument("--channels", nargs="+",
                        help="datasets as group/name, one panel each (default: chosen from the "
                             "record: each muscle's force and temperature, each drive's power, "
                             "the load's angle or deflection)")
    steps = command("steps", "step responses with the rise and settling marks of tcpmsim analyze",
                    "a tcpmsim run's record")
    steps.add_argument("--reference", default="controller/reference", help="(default: %(default)s)")
    steps.add_argument("--response", default="load/force", help="(default: %(default)s)")
    steps.add_argument("--lower", type=float, default=0.1,
                       help="fraction of the step y_f - y0 (default: 0.1)")
    steps.add_argument("--upper", type=float, default=0.9,
                       help="fraction of the step y_f - y0 (default: 0.9)")
    steps.add_argument("--settling-band", type=float, default=0.02,
                       help="settled within this fraction of |y_f - y0| (default: 0.02)")
    steps.add_argument("--to-reference", action="store_true",
                       help="the control tasks' rise times instead: from the response at the step "
                            "to the new reference, a cross where it is not reached (no settling)")
    bode = command("bode", "Bode plot of a sweep task with its -3 dB bandwidth",
                   "tcpmsim control-tasks' file")
    bode.add_argument("--task", help="the sweep task (default: the only one)")
    sweep = command("sweep", "a sweep's metric: heat map over --x and --y, or scatter over --x",
                    "tcpmsim sweep's file")
    sweep.add_argument("--x", required=True, help="a summary column (a parameter path)")
    sweep.add_argument("--y", help="a second parameter: a heat map (a coloured scatter off a grid)")
    sweep.add_argument("--metric", required=True, help="a summary column (a metric's name)")
    sweep.add_argument("--colour", help="scatter only: colour the points by this column "
                                        "(a legend for a few values, else a colour bar)")
    sweep_traces = command("sweep-traces", "one channel of every run a sweep stored, labelled by "
                                           "the run's parameters", "tcpmsim sweep's file")
    sweep_traces.add_argument("--channel", required=True, help="a channel as group/name")
    sweep_traces.add_argument("--scenario", help="the sweep's scenario (default: the only one "
                                                 "recording the channel)")
    sweep_traces.add_argument("--runs", type=int, nargs="+", help="run ids (default: all)")
    bundle = command("bundle", "a bundle's per-muscle temperature spread", "a tcpmsim run's record")
    bundle.add_argument("--bundle", default="bundle", help="the bundle's name (default: %(default)s)")
    bundle.add_argument("--time", type=float, help="time of the cross-section [s] (default: the end)")
    command("fit", "tcpmsim fit's measured and fitted outputs, the windows and the residual",
            "tcpmsim fit's --out directory (default -o: DIR/fit.png)")
    command("discovery", "tcpmsim discover's residuals before and after, and its diagnostic",
            "tcpmsim discover's output directory (-o: the directory for residuals.png and "
            "diagnostic.png)")
    return top


def main(argv=None):
    arguments = parser().parse_args(argv)
    try:
        if (arguments.output and arguments.command != "discovery"
                and not arguments.output.lower().endswith((".png", ".svg"))):
            raise PlotError(f"{arguments.output}: the output must end in .png or .svg")
        if arguments.command == "traces":
            plot_traces(arguments.file, arguments.channels, output_of(arguments, ".png"))
        elif arguments.command == "steps":
            plot_steps(arguments.file, arguments.reference, arguments.response,
                       output_of(arguments, "_steps.png"), arguments.lower, arguments.upper,
                       arguments.settling_band, arguments.to_reference)
        elif arguments.command == "bode":
            plot_bode(arguments.file, arguments.task, output_of(arguments, "_bode.png"))
        elif arguments.command == "sweep":
            plot_sweep(arguments.file, arguments.x, arguments.y, arguments.metric,
                       output_of(arguments, f"_{arguments.metric}.png"), arguments.colour)
        elif arguments.command == "sweep-traces":
            suffix = "_" + arguments.channel.replace("/", "_") + ".png"
            plot_sweep_traces(arguments.file, arguments.channel, output_of(arguments, suffix),
                              arguments.scenario, arguments.runs)
        elif arguments.command == "fit":
            plot_fit(arguments.file, arguments.output)
        elif arguments.command == "discovery":
            plot_discovery(arguments.file, arguments.output)
        else:
            plot_bundle(arguments.file, arguments.bundle, arguments.time,
                        output_of(arguments, "_bundle.png"))
    except PlotError as error:
        fail(error)
