"""Writing a scene out as something to hand over: a standalone VPython program.

This package sits on the physics and the scenes and under both front ends: the command line
(`main.py --vpython FILE.py`) and the browser page (its Download program button) call it. It never
imports vpython, the command line or the browser view.

    vpython_program   the program for a configured scene, as text
    exact_curve       its exact-solution lines, where a closed form exists
    lines             numbers and comments as the program spells them
    files             writing the file whole (a temporary file renamed over the target)
"""
from .files import OutputError, check_path, write_program
from .lines import ProgramError
from .vpython_program import program

__all__ = ["OutputError", "ProgramError", "check_path", "program", "write_program"]
