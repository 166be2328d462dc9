"""Stepping one mass fast: the vector update, written out in plain floats by the program itself.

Why: numpy pays about a microsecond for every call, whatever the size of the array. One
Euler-Cromer step of the page's spring is some 19 numpy calls on arrays of 3 numbers, so one
mass stepped with numpy runs several times slower than the page's own vpython loop, although the
arithmetic is only about 40 additions and multiplications of floats. A second, hand-written copy
of every force law in components would be fast, but it would be a second copy to keep right.

How: the one copy of the physics (forces.py, integrators.py) writes the fast copy.

1. Trace. Take one step of the integrator on a state whose numbers are :class:`Traced`: each
   +, −, ×, ÷, √ or cos of them works out its value and also writes one line of Python on a
   :class:`Tape`, such as ``_7 = _5 * 0.0001``. numpy's object arrays do the broadcasting, so the
   force and integrator code runs unchanged. Where the code decides something from a number
   (Spring asks whether |L| is zero before it divides by |L|), the tape records a guard.
2. Compile. The tape becomes the body of a loop over plain Python floats, one local variable per
   component: the page's update as a hand calculation would write it (``loop.source`` shows it).
3. Run. The loop takes steps until it has done the number asked, or a guard fails, or the
   arithmetic raises (÷ 0, √ of a negative, cos of inf). Then the caller takes that step with
   numpy, which gives inf or NaN as usual, and traces again from there.

The loop does the same IEEE double operations as the numpy step, in the same order, so the two
agree to round-off (numpy's cos may differ from math.cos in the last bit; tests/test_compiled.py
compares them over every integrator and force).
"""
from __future__ import annotations

import math
import numbers
import operator
import re

import numpy as np

from .state import State

# The loop's cost grows with the number of components (masses × dimensions); numpy's hardly does
# until its fixed cost per call is spread over enough numbers. Measured per step: 3-D, 32 masses
# 36 µs against 45 µs with numpy, 64 masses 63 against 60 µs; 1-D, 64 masses 24 against 43 µs.
MAX_COMPONENTS = 96
# After this many guard failures in one run (a mass sitting on its anchor, say), stop tracing.
MAX_TRACES = 8


class Untraceable(TypeError):
    """The step did something a traced number cannot follow (float(), an unknown function)."""


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

    def __neg__(self):
        return self.tape.write(f"-{self.name}", -self.value)

    def __abs__(self):
        return self.tape.write(f"abs({self.name})", abs(self.value))

    __hash__ = None

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

    def __float__(self):
        raise Untraceable("the step turns a traced number into a float")

    __int__ = __index__ = __float__


class CompiledLoop:
    """Steps of one integrator on one system, as a loop over floats (see the module's docstring).

    Built by :func:`compile_loop`. :meth:`advance` takes the steps, and falls back to the numpy
    step function for a step the loop cannot take.
    """

    def __init__(self, step, forces, dt: float, state: State):
        self.step, self.forces, self.dt = step, tuple(forces), float(dt)
        self.shape, self.m = state.r.shape, state.m
        self.traces = 0
        self.source = ""
        self._loop = None
        self._trace(state)

    def _trace(self, state: State):
        """Trace one step from `state` and compile it; on failure, leave the numpy step in charge."""
        self.traces += 1
        self._loop = None
        try:
            tape = Tape()
            size = state.r.size
            r = np.array([tape.input(f"r{i}", x) for i, x in enumerate(state.r.ravel())], dtype=object)
            p = np.array([tape.input(f"p{i}", x) for i, x in enumerate(state.p.ravel())], dtype=object)
            t = tape.input("t", state.t)
            new = self.step(State(t=t, r=r.reshape(self.shape), p=p.reshape(self.shape), m=self.m),
                            self.forces, self.dt)
            outputs = [new.t, *np.asarray(new.r).ravel(), *np.asarray(new.p).ravel()]
            if len(outputs) != 1 + 2 * size:
                raise Untraceable("the step changed the number of masses")
            names = ["t"] + [f"r{i}" for i in range(size)] + [f"p{i}" for i in range(size)]
            self.source = _loop_source(tape, names, [tape.operand(x) for x in outputs])
            namespace = {"_sqrt": math.sqrt, "_cos": math.cos, "_sin": math.sin, "_pow": math.pow,
                         **tape.constants}
            exec(compile(self.source, "<compiled step>", "exec"), namespace)
            self._loop = namespace["advance"]
        except Exception:   # whatever the trace cannot follow, the numpy step still can
            self._loop = None

    def advance(self, state: State, done: int, stop: int, *, every: int, total: int, record) -> State:
        """Step from step number `done` to `stop`; returns the state after the last one.

        After each step i, if i is a multiple of `every` or i == total, calls
        record((t, r_0, r_1, ..., p_0, p_1, ...)) with the components of r and p flattened.
        """
        while done < stop:
            if self._loop is not None:
                done, values = self._loop(_flat(state), done, stop, every, total, record)
                state = self._state(values)
                if done == stop:
                    break
            # The loop stopped short (or there is none): one numpy step, then maybe trace again.
            state = self.step(state, self.forces, self.dt)
            done += 1
            if done % every == 0 or done == total:
                record(tuple(_flat(state)))
            if self.traces < MAX_TRACES:
                self._trace(state)
        return state

    def _state(self, values) -> State:
        size = len(values) // 2
        r = np.array(values[1:size + 1]).reshape(self.shape, order="C")
        p = np.array(values[size + 1:]).reshape(self.shape, order="C")
        return State(t=values[0], r=np.asfortranarray(r), p=np.asfortranarray(p), m=self.m)


def _flat(state: State) -> list:
    """[t, r_0, r_1, ..., p_0, p_1, ...]: the loop's variables, as plain floats."""
    return [state.t, *state.r.ravel().tolist(), *state.p.ravel().tolist()]


def _loop_source(tape: Tape, names: list[str], outputs: list[str]) -> str:
    """Python source of the loop: the tape's lines, with the variables updated at the end."""
    needed = set(outputs)
    body = []
    for name, expression in reversed(tape.lines):      # keep only lines the results need
        if name == "" or name in needed:
            body.append((name, expression))
            needed.update(re.findall(r"\b_\d+\b", expression))
    body.reverse()
    state = ", ".join(names)
    lines = [
        "def advance(values, done, stop, every, total, record):",
        f"    {state} = values",
        "    while done < stop:",
        "        try:",
    ]
    for name, expression in body:
        lines.append(f"            if not ({expression}): break" if name == ""
                     else f"            {name} = {expression}")
    lines += [
        "        except (ArithmeticError, ValueError):",
        "            break",
        f"        {state} = {', '.join(outputs)}",
        "        done += 1",
        "        if done % every == 0 or done == total:",
        f"            record(({state},))",
        f"    return done, [{state}]",
    ]
    return "\n".join(lines) + "\n"


def compile_loop(step, forces, dt: float, state: State) -> CompiledLoop | None:
    """A compiled loop for this step function and system, or None where numpy is as fast.

    Worth it for up to MAX_COMPONENTS numbers (32 masses in 3-D); returns None if the first
    trace fails, so the caller keeps to the numpy step.
    """
    if state.r.size > MAX_COMPONENTS:
        return None
    loop = CompiledLoop(step, forces, dt, state)
    return loop if loop._loop is not None else None
