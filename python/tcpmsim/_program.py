"""The console script `tcpmsim` of the wheel: runs the program bundled in the package
(tcpmsim/_bin/tcpmsim), with tcpmsim-plot (for discover's pictures) the one installed beside
this script."""
import os
import shutil
import sys


def main():
    program = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_bin", "tcpmsim")
    if not os.path.exists(program):
        sys.exit(f"tcpmsim: the program is not in this installation ({program}); "
                 "install the wheel, or run build/tcpmsim from a source tree")
    beside = os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), "tcpmsim-plot")
    plot = beside if os.path.exists(beside) else shutil.which("tcpmsim-plot")
    if plot and "TCPMSIM_PLOT_TOOL" not in os.environ:
        os.environ["TCPMSIM_PLOT_TOOL"] = plot
    os.execv(program, [program] + sys.argv[1:])
