"""Stepping a few masses fast: the engine's tick, written out in plain floats by the program itself.

Why: numpy pays about a microsecond for every call, whatever the size of the array. One
Euler-Cromer step of the page's spring is some 19 numpy calls on arrays of 3 numbers, so one
mass stepped with numpy runs several times slower than the page's own vpython loop, although the
arithmetic is only about 40 additions and multiplications of floats. A second, hand-written copy
of every force law in components would be fast, but it would be a second copy to keep right.

How: the one copy of the physics (physics/forces/, integrators.py) writes the fast copy.

1. Trace. Take one tick of the engine (physics/simulate.py: the integrator's step, the forces'
   stop rules and the work meter) on numbers that are :class:`Traced`: each
   +, −, ×, ÷, √ or cos of them works out its value and also writes one line of Python on a
   :class:`Tape`, such as ``_7 = _5 * 0.0001``. numpy's object arrays do the broadcasting, so the
   force and integrator code runs unchanged. Where the code decides something from a number
   (Spring asks whether |L| is zero before it divides by |L|), the tape records a guard. Where a
   force chooses between two values at every step (friction: moving or at rest), it writes
   physics.forces.where, which the tape writes as ``_9 = (_7 if _8 else 0.0)``: no guard.
2. Compile. The tape becomes the body of a loop over plain Python floats, one local variable per
   component: the page's update as a hand calculation would write it (``loop.source`` shows it).
3. Run. The loop takes steps until it has done the number asked, or a guard fails, or the
   arithmetic raises (÷ 0, √ of a negative, cos of inf). Then the engine takes that step with
   numpy, which gives inf or NaN as usual, and traces again from there. The time of each step is
   t = t0 + n·Δt from its number n, as in the engine.

A force the trace cannot follow (one that calls float() on its numbers, or a numpy function such
as np.exp that traced numbers do not know) leaves the numpy tick in charge, several times slower.
That is never silent: the first time, an :class:`UntracedWarning` names the force and what it did
(once per force and reason in a process); the command line shows it as one line on stderr.

Why not numba: measured on the user command (docs/performance.md), importing and compiling with
numba costs as much as it saves at 10⁶ steps, it cannot compile physics/forces/ as written, and it
adds some 200 MB; this module is a few hundred lines and keeps one copy of the physics.

The loop does the same IEEE double operations as the numpy tick, in the same order, so the two
agree to round-off (numpy's cos may differ from math.cos in the last bit; tests/test_compiled.py
compares them over every integrator and force).
"""
from __future__ import annotations

import math
import numbers
import operator
import re
import traceback
import warnings

import numpy as np

from .forces import Force


# The loop's cost grows with the number of components (masses × dimensions); numpy's hardly does
# until its fixed cost per call is spread over enough numbers. Measured per step: 3-D, 32 masses
# 36 µs against 45 µs with numpy, 64 masses 63 against 60 µs; 1-D, 64 masses 24 against 43 µs.
MAX_COMPONENTS = 96
# After this many guard failures in one run (a mass sitting on its anchor, say), stop tracing.
MAX_TRACES = 8


class Untraceable(TypeError):
    """The step did something a traced number cannot follow (float(), an unknown function)."""


class UntracedWarning(RuntimeWarning):
    """The fast loop cannot trace a force, so the engine steps it with numpy: one line that says
    which force and why."""


_REPORTED: set[str] = set()     # the reasons already warned about in this process


def untraced_reason(problem: Exception) -> str:
    """What the trace could not follow, naming the force where the failure was inside one:
    `the force EddyBrake (in __call__: TypeError: ...)`."""
    culprit = "the step"
    for frame, _ in traceback.walk_tb(problem.__traceback__):
        owner = frame.f_locals.get("self")
        if isinstance(owner, Force) or (frame.f_code.co_name == "__call__" and not isinstance(owner, Traced)):
            culprit = f"the force {type(owner).__name__} (in {frame.f_code.co_name})"
    what = " ".join(f"{type(problem).__name__}: {problem}".split())
    return f"{culprit} cannot be traced for the fast loop ({what})"


def warn_untraced(problem: Exception) -> None:
    """Warn once per reason that the numpy tick, several times slower, steps this system."""
    reason = untraced_reason(problem)
    if reason not in _REPORTED:
        _REPORTED.add(reason)
        warnings.warn(f"{reason}: it runs with numpy, several times slower (physics/compiled.py)",
                      UntracedWarning, stacklevel=2)


class Tape:
    """The lines of Python one traced step writes, in order, with its guards."""

    def __init__(self):
        self.lines: list[tuple[str, str]] = []   # (name, expression); guards have name ""
        self.constants: dict[str, float] = {}    # names for inf and NaN, which have no literal
        self._seen: dict[str, Traced] = {}        # expression -> its name (no sum done twice)

    def input(self, name: str, value: float) -> "Traced":
        return Traced(self, name, float(value))

    def write(self, expression: str, value) -> "Traced":
        if expression in self._seen:
            return self._seen[expression]
        traced = Traced(self, f"_{len(self.lines)}", value)
        self.lines.append((traced.name, expression))
        self._seen[expression] = traced
        return traced

    def guard(self, condition: str, holds: bool):
        self.lines.append(("", condition if holds else f"not ({condition})"))

    def operand(self, x) -> str:
        """How x is spelled in the loop: a traced name, or a constant."""
        if isinstance(x, Traced):
            return x.name
        if isinstance(x, (bool, np.bool_)):
            return repr(bool(x))
        if not isinstance(x, numbers.Real):
            raise Untraceable(f"cannot trace an operation with {type(x).__name__}")
        value = float(x)
        if math.isfinite(value):
            negative = math.copysign(1.0, value) < 0          # −0.0 too
            return f"({value!r})" if negative else repr(value)
        name = f"_c{len(self.constants)}"
        self.constants[name] = value
        return name


def _value(x):
    return x.value if isinstance(x, Traced) else float(x)


def _operator(symbol: str, compute, reflected: bool = False):
    """The method for one arithmetic or comparison operator of Traced (reflected: other ∘ self)."""
    def method(self, other):
        if isinstance(other, np.ndarray):
            return NotImplemented       # numpy broadcasts, and calls us once per element
        a, b = (other, self) if reflected else (self, other)
        return self._binary(symbol, a, b, compute(_value(a), _value(b)))
    return method


class Traced:
    """A number whose arithmetic is written down on a tape as well as worked out."""

    __slots__ = ("tape", "name", "value")

    def __init__(self, tape: Tape, name: str, value):
        self.tape, self.name, self.value = tape, name, value

    def _binary(self, symbol, a, b, value):
        tape = self.tape
        left, right = tape.operand(a), tape.operand(b)
        # x − 0, x × 1 and x ÷ 1 are exactly x (signed zeros and NaN included): write nothing.
        exact = (symbol == "-" and right == "0.0") or (symbol in ("*", "/") and right == "1.0")
        if isinstance(a, Traced) and exact:
            return a
        return tape.write(f"{left} {symbol} {right}", value)

    __add__ = _operator("+", operator.add)
    __radd__ = _operator("+", operator.add, reflected=True)
    __sub__ = _operator("-", operator.sub)
    __rsub__ = _operator("-", operator.sub, reflected=True)
    __mul__ = _operator("*", operator.mul)
    __rmul__ = _operator("*", operator.mul, reflected=True)
    __truediv__ = _operator("/", operator.truediv)
    __rtruediv__ = _operator("/", operator.truediv, reflected=True)
    __lt__ = _operator("<", operator.lt)
    __le__ = _operator("<=", operator.le)
    __gt__ = _operator(">", operator.gt)
    __ge__ = _operator(">=", operator.ge)
    __eq__ = _operator("==", operator.eq)
    __ne__ = _operator("!=", operator.ne)

    def __pow__(self, other):
        # math.pow, not **: a negative base to a fractional power raises (numpy gives NaN there)
        # instead of turning into a complex number.
        if isinstance(other, np.ndarray):
            return NotImplemented
        exponent = self.tape.operand(other)
        return self.tape.write(f"_pow({self.name}, {exponent})", math.pow(self.value, _value(other)))

    def __rpow__(self, other):
        base = self.tape.operand(other)
        return self.tape.write(f"_pow({base}, {self.name})", math.pow(_value(other), self.value))

    def __neg__(self):
        return self.tape.write(f"-{self.name}", -self.value)

    def __abs__(self):
        return self.tape.write(f"abs({self.name})", abs(self.value))

    __hash__ = None

    def choose(self, a, b):
        """`a if self else b`, written as that (physics/forces/base.py's where): a choice made at
        every step of the loop, so no guard, and no retrace when it goes the other way."""
        tape = self.tape
        value = _value(a) if self.value else _value(b)
        if a is True and b is False or (isinstance(a, np.bool_) and a and isinstance(b, (bool, np.bool_)) and not b):
            return self                                   # `True if c else False` is c itself
        if not isinstance(a, Traced) and not isinstance(b, Traced) and _value(a) == _value(b) and \
                math.copysign(1.0, _value(a)) == math.copysign(1.0, _value(b)):
            return a                                      # the same constant either way
        return tape.write(f"({tape.operand(a)} if {self.name} else {tape.operand(b)})", value)

    def __bool__(self):
        # The step decides something from this number: the loop must check it decides alike.
        holds = bool(self.value)
        self.tape.guard(self.name, holds)
        return holds

    # numpy calls these methods for np.sqrt, np.cos, ... on arrays of objects.
    def sqrt(self):
        return self.tape.write(f"_sqrt({self.name})", math.sqrt(self.value))

    def cos(self):
        return self.tape.write(f"_cos({self.name})", math.cos(self.value))

    def sin(self):
        return self.tape.write(f"_sin({self.name})", math.sin(self.value))

    def exp(self):
        return self.tape.write(f"_exp({self.name})", math.exp(self.value))

    def __float__(self):
        raise Untraceable("the step turns a traced number into a float")

    __int__ = __index__ = __float__


class CompiledLoop:
    """Ticks of the engine on one system, as a loop over floats (see the module's docstring).

    `tick(t, t_next, *arrays) -> arrays` is the engine's one tick (physics/simulate.py): the
    integrator's step, and the work meter where it runs. The loop computes the time of each step
    from its number, t = t0 + n·Δt, exactly as the engine does. Built by :func:`compile_loop`;
    :meth:`advance` runs it, and returns early where the loop cannot take a step (then the engine
    takes that step with numpy and calls :meth:`retrace`).
    """

    def __init__(self, tick, arrays, *, t0: float, dt: float):
        self.tick, self.t0, self.dt = tick, float(t0), float(dt)
        self.shapes = [np.shape(a) for a in arrays]
        self.traces = 0
        self.source = ""
        self._loop = None
        self.retrace(arrays, step=0)

    @property
    def ready(self) -> bool:
        return self._loop is not None

    def retrace(self, arrays, *, step: int) -> None:
        """Trace one tick from these arrays at step number `step`, and compile it; on failure,
        leave the numpy tick in charge."""
        self.traces += 1
        self._loop = None
        self.failure = None
        try:
            tape = Tape()
            names = [f"a{n}_{i}" for n, a in enumerate(arrays) for i in range(np.size(a))]
            flat = iter([tape.input(name, x) for name, x in zip(names, _flat(arrays))])
            traced = [np.array([next(flat) for _ in range(np.size(a))], dtype=object).reshape(np.shape(a))
                      for a in arrays]
            t = tape.input("t", self.t0 + step * self.dt)
            t_next = tape.input("t_next", self.t0 + (step + 1) * self.dt)
            outputs = [x for a in self.tick(t, t_next, *traced) for x in np.asarray(a).ravel()]
            if len(outputs) != len(names):
                raise Untraceable("the tick changed the number of values")
            self.source = _loop_source(tape, names, [tape.operand(x) for x in outputs])
            namespace = {"_sqrt": math.sqrt, "_cos": math.cos, "_sin": math.sin, "_exp": math.exp, "_pow": math.pow,
                         "_t0": self.t0, "_dt": self.dt, **tape.constants}
            exec(compile(self.source, "<compiled tick>", "exec"), namespace)
            self._loop = namespace["advance"]
        except (ArithmeticError, ValueError):   # the state itself (√ of a negative, overflow):
            self._loop = None                     # numpy gives NaN or inf there, as it should
        except Exception as problem:   # whatever the trace cannot follow, the numpy tick still can
            self._loop = None
            self.failure = problem
            warn_untraced(problem)

    def advance(self, arrays, done: int, stop: int, recorder):
        """Tick from step number `done` towards `stop`; returns (done, arrays).

        After a tick that reaches step number recorder.mark, keeps the step number and every
        component of the arrays: added to recorder.rows (a flat list of floats) where the recorder has a stride (the
        next mark is done + stride, at most recorder.last), else through recorder.record(done,
        values=...), which returns the next mark. Returns early (done < stop) where the loop
        cannot take a step.
        """
        done, recorder.mark, values = self._loop(_flat(arrays), done, stop, recorder.mark,
                                                 lambda done, values: recorder.record(done, values=values),
                                                 recorder.stride, recorder.last, recorder.rows.extend)
        return done, self.unflatten(values)

    def unflatten(self, values) -> list:
        arrays, start = [], 0
        for shape in self.shapes:
            size = int(np.prod(shape))
            arrays.append(np.array(values[start:start + size], dtype=float).reshape(shape))
            start += size
        return arrays


def _flat(arrays) -> list:
    """Every component of the arrays, in order, as plain floats."""
    return [x for a in arrays for x in np.asarray(a, dtype=float).ravel().tolist()]


def _loop_source(tape: Tape, names: list[str], outputs: list[str]) -> str:
    """Python source of the loop: the tape's lines, with the variables updated at the end."""
    needed = set(outputs)
    body = []
    for name, expression in reversed(tape.lines):      # keep only lines the results need
        if name == "" or name in needed:
            body.append((name, expression))
            needed.update(re.findall(r"\b_\d+\b", expression))
    body.reverse()
    used = " ".join(expression for _, expression in body) + " " + " ".join(outputs)
    state = ", ".join(names)
    lines = [
        "def advance(values, done, stop, mark, record, stride, last, keep):",
        f"    {state}, = values",
        "    while done < stop:",
    ]
    # t = t0 + n·Δt from the step number, never a running sum (only where a force reads t).
    if re.search(r"\bt\b", used):
        lines.append("        t = _t0 + done * _dt")
    if re.search(r"\bt_next\b", used):
        lines.append("        t_next = _t0 + (done + 1) * _dt")
    lines.append("        try:")
    for name, expression in body:
        lines.append(f"            if not ({expression}): break" if name == ""
                     else f"            {name} = {expression}")
    lines += [
        "            pass",
        "        except (ArithmeticError, ValueError):",
        "            break",
        f"        {state}, = {', '.join(outputs)},",
        "        done += 1",
        "        if done == mark:",
        "            if stride:",
        f"                keep((done, {state}))",
        "                mark = done + stride",
        "                if mark > last:",
        "                    mark = last",
        "            else:",
        f"                mark = record(done, ({state},))",
        f"    return done, mark, [{state}]",
    ]
    return "\n".join(lines) + "\n"


def compile_loop(tick, arrays, *, t0: float, dt: float) -> CompiledLoop | None:
    """A compiled loop for this tick and these arrays, or None where numpy is as fast.

    Worth it for up to MAX_COMPONENTS numbers in r (32 masses in 3-D); returns None if the
    first trace fails, so the engine keeps to the numpy tick (with an UntracedWarning, once,
    where a force could not be traced).
    """
    if np.size(arrays[0]) > MAX_COMPONENTS:
        return None
    loop = CompiledLoop(tick, arrays, t0=t0, dt=dt)
    return loop if loop.ready else None
