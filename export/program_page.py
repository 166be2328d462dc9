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
    page.drawn([ball], [pos], [p], {"p": [parrow], ...})   # after the objects
    ...
        page.stepped(0, n + 1, m, Fnet, p, pos)     # after each update: for the Step read-out

and it asks at which step the question time falls (`n_until`, as a headless run reaches it) so that
a new Δt from a slider or the address still prints its answer at the step `--headless` stops at.
"""
from __future__ import annotations

from .lines import commented

PAGE = "page"   # the name the program gives the page's object


def controls_lines() -> list[str]:
    """The controls section, right after the constants."""
    return ["", "# ---- the page's controls: Run/Pause, Step, Reset, the sliders and the arrows are the",
            "# offline page's, around this program; it tells the page what it drew and each step ----",
            commented(f"{PAGE} = offline_page()", "the page around this program (export/offline_page.js)")]


def drawn_line(*, single: bool, arrows: dict[str, str]) -> str:
    """After the objects and the arrows: the masses, their start, and each kind of arrow's objects."""
    kinds = ", ".join(f'"{kind}": {objects}' for kind, objects in arrows.items())
    masses = "[ball], [pos], [p]" if single else "balls, pos, p"
    return commented(f"{PAGE}.drawn({masses}, {{{kinds}}})", "what the page's check boxes show or hide")


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


def question_lines() -> list[str]:
    """Before the loop: the step at which t = n·Δt reaches the question time, as a headless run
    counts it (physics/recording.py's steps_to_reach), whatever Δt the page gives."""
    return [commented("n_until = ceil(until/dt - 1e-9)", "the step that reaches the question time")]


QUESTION_CONDITION = "n == n_until"
