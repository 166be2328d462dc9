"""The command line's reports: headless runs, the final state as text or JSON, CSV files, the step table
and the figure (--plot). Nothing here imports vpython or the browser."""
