"""The muscle as an FMU, driven by a master written here: what Simulink, OpenModelica or FMPy do
with `tcpmsim export-fmu`'s file, in fifty lines of ctypes over the FMI 2.0 C functions.

The FMU is configs/ch7_control/external_force.yaml (the chapter-7 force bench with the loop
open); the master closes it with the thesis' PI (7.7)-(7.9) at the drive's 20 Hz, as
examples/own_controller.py does through tcpmsim.Simulator, and checks that the self-sensed
force it read equals the built-in PID's record bit for bit.

    examples/fmu_master.py          # needs the program: build/tcpmsim (or TCPMSIM=...)
"""
import ctypes
import math
import os
import subprocess
import tempfile
import xml.etree.ElementTree as ElementTree
import zipfile

import numpy as np

import tcpmsim

PROGRAM = os.environ.get("TCPMSIM", "build/tcpmsim")
CONFIG = "configs/ch7_control/external_force.yaml"

# FMI 2.0's C types (fmu/fmi2/fmi2FunctionTypes.h); the logger's varargs are not read: the FMU
# passes its whole message as the format.
LOGGER = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                          ctypes.c_char_p)


class Callbacks(ctypes.Structure):
    _fields_ = [("logger", LOGGER), ("allocateMemory", ctypes.c_void_p),
                ("freeMemory", ctypes.c_void_p), ("stepFinished", ctypes.c_void_p),
                ("componentEnvironment", ctypes.c_void_p)]


@LOGGER
def log(_environment, instance, status, category, message):
    print(f"  [{instance.decode()} {category.decode()}] {message.decode()}")


def real_function(library, name, *arguments):
    function = getattr(library, name)
    function.argtypes, function.restype = arguments, ctypes.c_int
    return function


with tempfile.TemporaryDirectory() as directory:
    fmu = os.path.join(directory, "muscle.fmu")
    subprocess.run([PROGRAM, "export-fmu", CONFIG, "-q", "-o", fmu,
                    "--outputs", "estimator.force,controller.reference,muscle.force"], check=True)
    unpacked = os.path.join(directory, "unpacked")
    zipfile.ZipFile(fmu).extractall(unpacked)
    description = ElementTree.parse(os.path.join(unpacked, "modelDescription.xml")).getroot()
    identifier = description.find("CoSimulation").get("modelIdentifier")
    reference = {v.get("name"): int(v.get("valueReference"))
                 for v in description.find("ModelVariables")}
    library = ctypes.CDLL(os.path.join(unpacked, "binaries", "linux64", identifier + ".so"))
    instantiate = library.fmi2Instantiate
    instantiate.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
                            ctypes.POINTER(Callbacks), ctypes.c_int, ctypes.c_int]
    instantiate.restype = ctypes.c_void_p
    pointer = ctypes.c_void_p
    setup = real_function(library, "fmi2SetupExperiment", pointer, ctypes.c_int, ctypes.c_double,
                          ctypes.c_double, ctypes.c_int, ctypes.c_double)
    enter = real_function(library, "fmi2EnterInitializationMode", pointer)
    leave = real_function(library, "fmi2ExitInitializationMode", pointer)
    values = ctypes.POINTER(ctypes.c_uint), ctypes.c_size_t, ctypes.POINTER(ctypes.c_double)
    get_real = real_function(library, "fmi2GetReal", pointer, *values)
    set_real = real_function(library, "fmi2SetReal", pointer, *values)
    do_step = real_function(library, "fmi2DoStep", pointer, ctypes.c_double, ctypes.c_double,
                            ctypes.c_int)
    terminate = real_function(library, "fmi2Terminate", pointer)
    library.fmi2FreeInstance.argtypes = [pointer]

    callbacks = Callbacks(log, None, None, None, None)
    resources = "file://" + os.path.join(unpacked, "resources")
    instance = instantiate(b"muscle", 1, description.get("guid").encode(), resources.encode(),
                           ctypes.byref(callbacks), 0, 0)
    assert instance, "fmi2Instantiate failed (see the log)"
    stop = float(description.find("DefaultExperiment").get("stopTime"))
    assert setup(instance, 0, 0.0, 0.0, 1, stop) == 0 and enter(instance) == 0
    assert leave(instance) == 0

    names = ["estimator.force", "controller.reference"]
    outputs = (ctypes.c_uint * 2)(*(reference[n] for n in names))
    read = (ctypes.c_double * 2)()
    power_reference = (ctypes.c_uint * 1)(reference["controller.power_command"])
    dt, kp, ti, low, high, integral = 0.05, 540.0, 1.0, 0.10, 3.12, 0.0
    estimates, t = [], 0.0
    for k in range(int(round(stop / dt)) + 1):
        t = k * dt
        assert get_real(instance, outputs, 2, read) == 0
        estimate, r = read[0], read[1]
        estimates.append(estimate)
        if k * dt >= stop:
            break
        if math.isfinite(estimate):  # (7.7)-(7.9), explicit Euler, back-calculation
            error = r - estimate
            demand = kp * (error + integral / ti)
            power = min(high, max(low, demand))
            integral += dt * (error - (demand - power) / kp)
        else:
            power, integral = low, 0.0
        assert set_real(instance, power_reference, 1, (ctypes.c_double * 1)(power)) == 0
        assert do_step(instance, t, dt, 1) == 0
    assert terminate(instance) == 0
    library.fmi2FreeInstance(instance)

builtin = tcpmsim.Scenario.from_yaml("configs/ch7_control/force_steps.yaml").run()
assert np.array_equal(np.asarray(estimates), builtin["estimator/force"], equal_nan=True), \
    "the FMU under this master is not the built-in PID's run"
print(f"FMU {identifier}: {len(estimates)} samples to t = {t:.0f} s under a PI written in "
      "Python over ctypes; the self-sensed force equals the built-in PID's record bit for bit")
