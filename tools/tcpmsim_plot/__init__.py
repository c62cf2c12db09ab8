"""tcpmsim-plot: pictures of tcpmsim's HDF5 files, on Debian's python3-h5py, numpy and matplotlib.

    tcpmsim-plot traces RECORD.h5 [--channels group/name ...]   time traces
    tcpmsim-plot steps RECORD.h5 --reference R --response Y       step responses, rise and
                                                                  settling marks (as analyze)
    tcpmsim-plot bode CONTROL_TASKS.h5 --task NAME                 Bode plot with the -3 dB point
    tcpmsim-plot sweep SWEEP.h5 --x P --y P --metric M             heat map over two parameters
    tcpmsim-plot sweep SWEEP.h5 --x P --metric M [--colour P]      parameter-metric scatter
    tcpmsim-plot sweep-traces SWEEP.h5 --channel group/name        a channel of every stored run
    tcpmsim-plot bundle RECORD.h5 [--bundle NAME]                  a bundle's per-muscle spread
    tcpmsim-plot fit FIT_OUT_DIR                                   measured and fitted outputs
    tcpmsim-plot discovery DISCOVER_OUT_DIR                        discover's residuals

Each writes PNG or SVG (by the extension of -o); temperatures are drawn in degC. Each picture's
figure comes from a function (traces_figure, steps_figure, ...) apart from the one that saves
it. Run as tools/tcpmsim-plot, as `python3 -m tcpmsim_plot` from tools/, or install tools/ with
pip for the entry point.
"""

__version__ = "0.1.0"
