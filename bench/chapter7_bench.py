"""What the fit and discover benchmarks share: the chapter-7 protocol's record (their
measurement) and the reference in the same run, one simulation of the base model replaying it."""
import os
import re
import subprocess


def protocol_record(tcpmsim, path):
    """Runs configs/discover/ch7_protocol.yaml (620 s at 16 Hz) into `path`."""
    subprocess.run([tcpmsim, "run", "configs/discover/ch7_protocol.yaml", "-q", "-o", path],
                   check=True)
    return path


def simulation_seconds(build, data):
    """The median time of one run of configs/discover/ch7_base.yaml replaying `data`."""
    output = subprocess.run(
        [os.path.join(build, "bench", "bench_integration"), "configs/discover/ch7_base.yaml", "5",
         "measurement.file=" + data], check=True, capture_output=True, text=True).stdout
    return float(re.search(r"median_seconds=([0-9.e+-]+)", output).group(1))
