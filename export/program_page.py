"""The lines the offline page adds to the program it runs: a controls section and two reports.

The offline page (export/offline_page.py) runs the handed-out Web VPython program itself, in
GlowScript. Its Run/Pause, Step, Reset, sliders and arrow check boxes are the page's, around the
program: the page owns the timing (it holds the program at `rate()` while paused and lets one
pass per Step) and restarts it for Reset or a new constant. The program owns the stepping: its
arithmetic is the handout's, line for line. It tells the page three things, through one object
it asks for in a section of its own after the constants:

    # ---- the page's controls ----
    page = offline_page()                           # the page around this program (...)
    ...
    page.constants({"m": m, "k": k, ...})          # the values it runs with
    page.rates(0, m, k, 0, 0, mag(v0))              # what limits Δt, as each force declares it
    page.check()                                    # the page refuses here what the command line would
    page.drawn([ball], [pos], [p], {"p": [parrow], ...}, ["mass"])   # after the objects
    ...
        page.stepped(0, n + 1, m, Fnet, p, pos, U, W)   # after each update: the Step read-out, the energy

and it asks at which step the question time falls (`n_until`, as a headless run reaches it) so that
a new Δt from a slider or the address still prints its answer at the step `--headless` stops at.

Everything the page shows of the physics comes from these lines, each read from a declaration:
the rates the stability judgement needs from each force's PROGRAM_RATES, the rules its constants
must keep from each force's RULES (friction's μ_s ≥ μ_k), each conservative force's potential
energy from its PROGRAM_ENERGY, and W_nc as the engine meters it (physics/energy.py: the power of
the forces that are not conservative, their own PROGRAM lines at the step's end, by the trapezoid
rule). The page's script only shows and sums them.
"""
from __future__ import annotations

import re

from .lines import commented, vector
from .program_forces import REST

PAGE = "page"   # the name the program gives the page's object


def controls_lines(case) -> list[str]:
    """The controls section, right after the constants (and the masses' lists): the page's object,
    the values the program runs with, and the check of the set-up before anything is drawn."""
    named = [name for name in case.setup.constants
             if (isinstance(case.constants.single.get(name), float) or name in case.used)
             and isinstance(case.setup.values.get(name), float)]
    values = "{" + ", ".join(f'"{name}": {name}' for name in named) + "}"
    return ["", "# ---- the page's controls: Run/Pause, Step, Reset, the sliders and the arrows are the",
            "# offline page's, around this program; it tells the page what it drew and each step ----",
            commented(f"{PAGE} = offline_page()", "the page around this program (export/offline_page.js)"),
            commented(f"{PAGE}.constants({values})", "the values this run has")] + check_lines(case)


def check_lines(case) -> list[str]:
    """Each mass's rates (what limits Δt: physics/stability.py, from each force's PROGRAM_RATES) and
    each force's RULES, before anything is drawn: the page refuses there, in the command line's
    words, a set-up the command line would refuse, and runs the file's own instead."""
    n, m = case.constants.name, case.m
    names = {"m": m, "speed": f"mag({n('v0')})"}
    terms = {"stiffness": [], "damping": [], "drag": []}
    body = []
    for force in case.model.forces:
        filled = {name: n(name) for name in force.program_values()} | names
        for kind, text in force.PROGRAM_RATES.items():
            terms[kind].append(text.format(**filled))
        for rule in force.RULES:
            said = '"' + re.sub(r"\{(\w+)\}", lambda found: '" + number(' + filled[found[1]] + ') + "',
                                rule.says) + '"'
            body += [f"if {rule.breaks.format(**filled)}:", f"    {PAGE}.refuse({said})"]
    rates = ", ".join(" + ".join(parts) or "0" for parts in terms.values())
    body.insert(0, commented(f"{PAGE}.rates({'0' if case.single else 'i'}, {m}, {rates}, {names['speed']})",
                             "k (N/m), b/m and the drag's ρCA|v|/m (1/s), at |v| (m/s)"))
    lines = ["", "# the page's check of this set-up, before anything is drawn: what limits Δt, and each force's rules"]
    lines += body if case.single else ["for i in range(len(r0)):"] + ["    " + line for line in body]
    return lines + [commented(f"{PAGE}.check()", "a set-up the command line would refuse stops here")]


def drawn_line(*, single: bool, arrows: dict[str, str]) -> str:
    """After the objects and the arrows: the masses, their start, each kind of arrow's objects, and
    each mass's label."""
    kinds = ", ".join(f'"{kind}": {objects}' for kind, objects in arrows.items())
    masses = "[ball], [pos], [p]" if single else "balls, pos, p"
    labels = '["mass"]' if single else "labels"
    return commented(f"{PAGE}.drawn({masses}, {{{kinds}}}, {labels})", "what the page's check boxes show or hide")


def arrow_objects(kinds, *, single: bool) -> dict[str, str]:
    """The program's objects of each kind of arrow (export/program_arrows.py's names), as lists."""
    split = ("pararrow", "perparrow", "parlabel", "perplabel")
    if single:
        objects = {"p": "[parrow]", "F_net": "[Farrow]", "split": "[" + ", ".join(split) + "]"}
    else:
        objects = {"p": "parrows", "F_net": "Farrows", "split": " + ".join(f"{name}s" for name in split)}
    objects["forces"] = "forcearrows + forcelabels"
    return {kind: objects[kind] for kind in kinds}


def stepped_line(*, single: bool, m: str, terms=()) -> str:
    """After one mass's update: the numbers the Step read-out writes out (m: the program's name of
    the mass's mass), and each force's term (`Fspring`, ...), which the description in words
    names (export/description.py; for a method that kicks once, each force at the step's start)."""
    i = "" if single else "[i]"
    return commented(f"{PAGE}.stepped({'0' if single else 'i'}, n + 1, {m}, Fnet, p{i}, pos{i}, "
                     f"[{', '.join(terms)}])", "for the page's Step read-out and description")


def exact_line(case, value: str) -> str:
    """After the exact curve's point: its value, for the page's error read-out."""
    return commented(f"{PAGE}.exact({'0' if case.single else 'i'}, {value})", "for the page's error read-out")


def energy_start_lines(case) -> list[str]:
    """Before the loop: each mass's energy at the start (K, U, W_nc = 0), and the power P of the
    forces that are not conservative there, for the trapezoid rule."""
    single = case.single
    first = ["W = 0" if single else "W.append(0)"] + _power(case, t="t", r=case.pos, p=case.p) + \
        ["P_was = P" if single else "P_was.append(P)"] + _energy(case) + \
        [commented(f"{PAGE}.energy({'0' if single else 'i'}, 0, K, U, W{case.index})", "the energy at the start")]
    if single:
        return [""] + first
    return ["", commented("W = []", "J: each mass's W_nc, the work of the forces that are not conservative"),
            commented("P_was = []", "W: their power at the step's start"),
            "for i in range(len(pos)):"] + ["    " + line for line in first]


def energy_lines(case) -> list[str]:
    """After one mass's update: its energy, K and each conservative force's potential energy U (its
    PROGRAM_ENERGY), and W_nc by the trapezoid rule, as the engine meters it: W += ½ (P_start +
    P_end) Δt."""
    i = case.index
    lines = _power(case, t="((n + 1)*dt)", r=case.pos, p=case.p)
    lines += [commented(f"W{i} = W{i} + 0.5*(P_was{i} + P)*dt", "J: W_nc by the trapezoid rule, as the engine meters it"),
              f"P_was{i} = P"] + _energy(case)
    return lines + [commented(f"{PAGE}.energy({'0' if case.single else 'i'}, n + 1, K, U, W{i})",
                              "for the page's energy graph and bars")]


def _energy(case) -> list[str]:
    """K = |p|²/2m and each conservative force's potential energy (its PROGRAM_ENERGY), of mass pos."""
    n = case.constants.name
    parts = []
    for force in case.model.forces:
        if force.conservative:
            energy = force.program_energy() if hasattr(force, "program_energy") else force.PROGRAM_ENERGY
            filled = {name: n(name) for name in force.program_values()} | {"r": case.pos, "m": case.m}
            parts.append(f'"{force.LABEL}": {energy.format(**filled)}')
    return [commented(f"K = dot({case.p}, {case.p})/(2*{case.m})", "J: kinetic energy |p|²/2m"),
            commented("U = {" + ", ".join(parts) + "}", "J: each conservative force's potential energy")]


def _power(case, *, t: str, r: str, p: str) -> list[str]:
    """P = F_nc · v at (t, r, p): the forces that are not conservative, each by its own PROGRAM
    lines, one that answers the others alone (only its part along v does work)."""
    forces = case.forces
    lines = [f"v = {p}/{case.m}"]
    terms = []
    for force in (force for force in forces.forces if not force.conservative):
        if force.responds:
            lines.append(f"{REST} = vector(0, 0, 0)")
        lines += [code for code, _ in forces._law(force, t=t, r=r, v="v", laws=False)]
        terms.append(force.TERM)
    total = " + ".join(terms) if terms else vector((0.0, 0.0, 0.0))
    return lines + [commented(f"P = dot({total}, v)", "W: the power of the forces that are not conservative")]


def question_lines() -> list[str]:
    """Before the loop: the step at which t = n·Δt reaches the question time, as a headless run
    counts it (physics/recording.py's steps_to_reach), whatever Δt the page gives."""
    return [commented("n_until = ceil(until/dt - 1e-9)", "the step that reaches the question time")]


QUESTION_CONDITION = "n == n_until"
