"""What both front ends write out: the scene as a program to hand out, and how numbers, colours
and files are written, so the page and the command line give the same.

This package sits on the physics and the scenes and under both front ends: the command line
(`main.py --vpython FILE.py`, --csv, --json, --plot) and the browser page (its Download program and
Download CSV buttons, its graphs) call it. It never imports vpython, the command line or the
browser view.

    vpython_program   the program for a configured scene, as text
    exact_curve       its exact-solution lines, where a closed form exists
    lines             numbers and comments as the program spells them
    numbers           the CSV header, and numbers in files: 15 significant digits, t with Δt's decimals
    palette           the colours and line widths of masses, exact curves and energies
    files             writing a file whole (a temporary file renamed over the target)
"""
from .files import OutputError, check_path, write_program
from .lines import ProgramError
from .vpython_program import program

__all__ = ["OutputError", "ProgramError", "check_path", "program", "write_program"]
