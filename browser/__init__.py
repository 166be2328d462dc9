"""The page in the browser: the loopback server, the frame loop, the 3-D scene, graphs and controls,
the real-time clock, and the notebook. The only part of the program that imports vpython."""
