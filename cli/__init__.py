"""The command line's own parts that are not reports: which options there are and which go together."""
