"""A Gymnasium-style environment: one muscle, the heating power as the action.

    from tcpmsim.env import MuscleEnv
    env = MuscleEnv("configs/ch7_control/external_force.yaml", target="force")
    observation, info = env.reset(seed=1)
    while True:
        observation, reward, terminated, truncated, info = env.step(env.action_space.sample())
        if terminated or truncated:
            break

It follows the Gymnasium API (reset, step, observation_space, action_space, metadata) without
needing the gymnasium package; when gymnasium is importable, `tcpmsim.env.GymnasiumMuscleEnv`
is the same environment as a registered `gymnasium.Env` ("tcpmsim/Muscle-v0"), its spaces
gymnasium Boxes.

The scenario's controller section is of type external (tcpmsim.Simulator): the action is held
as the drive's power for one step of `dt` (by default the drive's PWM period, the rate the
thesis' PID samples at), within the controller's power_limits. The observation is

    observe="estimate":  [self-sensed target (the ch.7 estimator), reference, last power]
    observe="state":     [true target, reference, last power, temperature, deflection, force]

in SI. The reference is the task the scenario's external controller reports
(controller/reference: its target and reference keys) unless `reference` gives one (a number or
a function of time in SI). The reward is minus the absolute tracking error of the true target,
in units of `error_scale`. An episode ends (truncated) at the scenario's duration.
"""

import math

import numpy as np

from ._core import Simulator

_TARGETS = {"force": ("muscle/force", "estimator/force", "N"),
            "deflection": ("muscle/deflection", "estimator/deflection", "m")}


class Box:
    """The bounds of an observation or action (gymnasium.spaces.Box's fields and methods)."""

    def __init__(self, low, high, seed=None):
        self.low = np.asarray(low, dtype=np.float64)
        self.high = np.asarray(high, dtype=np.float64)
        self.shape = self.low.shape
        self.dtype = np.dtype(np.float64)
        self._random = np.random.default_rng(seed)

    def seed(self, seed=None):
        self._random = np.random.default_rng(seed)
        return [seed]

    def sample(self):
        low = np.where(np.isfinite(self.low), self.low, -1.0)
        high = np.where(np.isfinite(self.high), self.high, 1.0)
        return self._random.uniform(low, high).astype(self.dtype)

    def contains(self, x):
        x = np.asarray(x, dtype=np.float64)
        return x.shape == self.shape and bool(np.all(x >= self.low) and np.all(x <= self.high))

    def __repr__(self):
        return f"Box({self.low}, {self.high}, {self.shape}, {self.dtype})"


class MuscleEnv:
    """A muscle under a Muscle Drive whose power the agent sets (see the module's text)."""

    metadata = {"render_modes": []}
    render_mode = None

    def __init__(self, scenario, target="force", reference=None, observe="estimate", dt=None,
                 error_scale=None, input_name=None):
        if target not in _TARGETS:
            raise ValueError(f"target: expected one of {sorted(_TARGETS)}, got {target!r}")
        if observe not in ("estimate", "state"):
            raise ValueError(f"observe: expected 'estimate' or 'state', got {observe!r}")
        self.simulator = scenario if isinstance(scenario, Simulator) else Simulator(scenario)
        inputs = self.simulator.inputs()
        if input_name is None:
            if len(inputs) != 1:
                raise ValueError("input_name: the scenario has external inputs "
                                 f"{sorted(inputs)}; name the one the action sets")
            input_name = next(iter(inputs))
        if input_name not in inputs:
            raise ValueError(f"input_name: no external input {input_name!r}; the scenario's: "
                             f"{sorted(inputs)}")
        self.input_name = input_name
        self.target = target
        self.observe = observe
        self._reference_key = None
        if reference is None:
            self._reference_key = self._scenario_reference(input_name, target)
        else:
            self.reference = (reference if callable(reference) else
                              (lambda t, r=float(reference): r))
        if dt is None:
            frequency = self.simulator.parameter("drive.pwm_frequency")
            dt = 1.0 / frequency
        self.dt = float(dt)
        low, high = inputs[input_name]["low"], inputs[input_name]["high"]
        self.action_space = Box([low], [high])
        self.error_scale = float(error_scale) if error_scale else (
            0.1 if target == "force" else 0.01)
        true_key, estimate_key, _ = _TARGETS[target]
        self._true_key, self._estimate_key = true_key, estimate_key
        size = 3 if observe == "estimate" else 6
        bound = np.full(size, np.inf)
        lower = -bound
        lower[2], bound[2] = low, high
        if observe == "state":
            lower[3] = 0.0  # the temperature [K]
        self.observation_space = Box(lower, bound)
        self._power = low
        self._outputs = None

    # The Gymnasium API ------------------------------------------------------------------------
    def reset(self, seed=None, options=None):
        """Starts an episode at t = 0; `seed` sets the scenario seed (the drive's measurement
        noise). While the estimator has no estimate yet (its filters filling) the power stays at
        its lower limit; the episode starts at the first sample it has one."""
        if seed is not None:
            self.action_space.seed(seed)
            self.observation_space.seed(seed)
        self._outputs = self.simulator.reset(seed=seed)
        self._power = self.action_space.low[0]
        self.simulator.set_input(self.input_name, self._power)
        while not math.isfinite(self._outputs[self._estimate_key]) and not self.simulator.finished:
            self._outputs = self.simulator.step(None, self.dt)
        return self._observation(), self._info()

    def step(self, action):
        if self._outputs is None:
            raise RuntimeError("step before reset")
        power = float(np.asarray(action, dtype=np.float64).reshape(-1)[0])
        power = min(max(power, self.action_space.low[0]), self.action_space.high[0])
        self._power = power
        self._outputs = self.simulator.step({self.input_name: power}, self.dt)
        error = self._outputs[self._true_key] - self.reference(self.simulator.time)
        reward = -abs(error) / self.error_scale
        truncated = self.simulator.finished
        return self._observation(), reward, False, truncated, self._info()

    def close(self):
        pass

    # --------------------------------------------------------------------------------------------
    def _scenario_reference(self, input_name, target):
        """The reference the external controller setting `input_name` reports, checked to be in
        the target's unit."""
        key = input_name.split(".")[0] + "/reference"
        units = self.simulator.result().units
        if key not in units:
            raise ValueError(f"reference: the scenario's controller reports no task ({key}: "
                             "give it target and reference keys), so give one here")
        if units[key] != _TARGETS[target][2]:
            raise ValueError(f"target: {target!r} is in {_TARGETS[target][2]}, but the scenario's "
                             f"task ({key}) is in {units[key]}")
        return key

    def reference(self, t):
        """The reference at `t`, the time reached: the scenario's task as its controller
        reports it (replaced when a reference is given)."""
        del t
        return self._outputs[self._reference_key]

    def _observation(self):
        t = self.simulator.time
        values = [self._outputs[self._estimate_key if self.observe == "estimate" else
                                self._true_key], self.reference(t), self._power]
        if self.observe == "state":
            values += [self._outputs["muscle/temperature"], self._outputs["muscle/deflection"],
                       self._outputs["muscle/force"]]
        return np.asarray(values, dtype=np.float64)

    def _info(self):
        return {"time": self.simulator.time,
                "true": self._outputs[self._true_key],
                "estimate": self._outputs[self._estimate_key],
                "reference": self.reference(self.simulator.time),
                "power": self._power}


try:  # the same environment as a gymnasium.Env, when gymnasium is there
    import gymnasium as _gymnasium
except ImportError:  # not in Debian: the plain class above serves
    _gymnasium = None

if _gymnasium is not None:
    class GymnasiumMuscleEnv(MuscleEnv, _gymnasium.Env):
        def __init__(self, *args, **kwargs):
            MuscleEnv.__init__(self, *args, **kwargs)
            self.action_space = _gymnasium.spaces.Box(self.action_space.low,
                                                      self.action_space.high, dtype=np.float64)
            self.observation_space = _gymnasium.spaces.Box(self.observation_space.low,
                                                           self.observation_space.high,
                                                           dtype=np.float64)

        def reset(self, seed=None, options=None):
            _gymnasium.Env.reset(self, seed=seed)
            return MuscleEnv.reset(self, seed=seed, options=options)

    _gymnasium.register(id="tcpmsim/Muscle-v0", entry_point=GymnasiumMuscleEnv)
