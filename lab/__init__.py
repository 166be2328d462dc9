"""Comparing the model with a real spring: measured data read in, the fit, and a mystery spring.

lab/ sits beside export/: it imports scenes/ and physics/ (and export/ to write a file whole), and
the command line (main.py), reports/ and browser/ use it. scipy is needed only by the fit, and is
optional: without it --fit says so in one line.
"""


class LabError(ValueError):
    """A measured-data file that cannot be read, or a comparison or fit that cannot be made: one line."""
