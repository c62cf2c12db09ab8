"""The tcpmsim-plot command line: one sub-command per kind of picture."""
import argparse

from tcpmsim_plot import __doc__ as overview
from tcpmsim_plot.bode import plot_bode
from tcpmsim_plot.bundle import plot_bundle
from tcpmsim_plot.common import PlotError, fail
from tcpmsim_plot.discovery import plot_discovery
from tcpmsim_plot.steps import plot_steps
from tcpmsim_plot.sweep import plot_sweep
from tcpmsim_plot.traces import DEFAULT_CHANNELS, plot_traces


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
    traces.add_argument("--channels", nargs="+", default=DEFAULT_CHANNELS,
                        help="datasets as group/name (default: %(default)s)")
    steps = command("steps", "step responses with rise-time marks", "a tcpmsim run's record")
    steps.add_argument("--reference", default="controller/reference", help="(default: %(default)s)")
    steps.add_argument("--response", default="load/force", help="(default: %(default)s)")
    steps.add_argument("--lower", type=float, default=0.1, help="fraction of the step (default: 0.1)")
    steps.add_argument("--upper", type=float, default=0.9, help="fraction of the step (default: 0.9)")
    bode = command("bode", "Bode plot of a sweep task with its -3 dB bandwidth",
                   "tcpmsim control-tasks' file")
    bode.add_argument("--task", help="the sweep task (default: the only one)")
    sweep = command("sweep", "a sweep's metric: heat map over --x and --y, or scatter over --x",
                    "tcpmsim sweep's file")
    sweep.add_argument("--x", required=True, help="a summary column (a parameter path)")
    sweep.add_argument("--y", help="a second parameter: a heat map (a coloured scatter off a grid)")
    sweep.add_argument("--metric", required=True, help="a summary column (a metric's name)")
    sweep.add_argument("--colour", help="scatter only: colour the points by this column")
    bundle = command("bundle", "a bundle's per-muscle temperature spread", "a tcpmsim run's record")
    bundle.add_argument("--bundle", default="bundle", help="the bundle's name (default: %(default)s)")
    bundle.add_argument("--time", type=float, help="time of the cross-section [s] (default: the end)")
    command("discovery", "tcpmsim discover's residuals before and after, and its diagnostic",
            "tcpmsim discover's output directory (-o: the directory for residuals.png and "
            "diagnostic.png)")
    return top


def main(argv=None):
    arguments = parser().parse_args(argv)
    try:
        if arguments.command == "traces":
            plot_traces(arguments.file, arguments.channels, output_of(arguments, ".png"))
        elif arguments.command == "steps":
            plot_steps(arguments.file, arguments.reference, arguments.response,
                       output_of(arguments, "_steps.png"), arguments.lower, arguments.upper)
        elif arguments.command == "bode":
            plot_bode(arguments.file, arguments.task, output_of(arguments, "_bode.png"))
        elif arguments.command == "sweep":
            plot_sweep(arguments.file, arguments.x, arguments.y, arguments.metric,
                       output_of(arguments, f"_{arguments.metric}.png"), arguments.colour)
        elif arguments.command == "discovery":
            plot_discovery(arguments.file, arguments.output)
        else:
            plot_bundle(arguments.file, arguments.bundle, arguments.time,
                        output_of(arguments, "_bundle.png"))
    except PlotError as error:
        fail(error)
