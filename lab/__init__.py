"""Comparing the model with a real spring: measured data read in, the fit, and a mystery spring.

lab/ sits beside export/: it imports scenes/ and physics/ (and export/ to write a file whole), and
the command line (main.py), reports/ and browser/ use it. numpy is all it needs (the fit is
its own Levenberg-Marquardt: lab/compare.py says why).
"""


class LabError(ValueError):
    """A measured-data file that cannot be read, or a comparison or fit that cannot be made: one line."""
