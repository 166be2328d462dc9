"""Reading a graph by clicking it: the script of export/graph_reading.py, which the offline page
(export/offline_page.py) holds too, so both pages read a graph with the one script."""
from export.graph_reading import GRAPH_READING

__all__ = ["GRAPH_READING"]
