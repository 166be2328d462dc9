"""Writing a scene out as something to hand over: a standalone VPython program (vpython_program).

This package sits on the physics and the scenes and under both front ends: the command line
(`main.py --vpython FILE.py`) and the browser page (its Download program button) call it. It never
imports vpython, the command line or the browser view.
"""
from .vpython_program import ProgramError, check_path, program, write_program

__all__ = ["ProgramError", "check_path", "program", "write_program"]
