"""Scenes: the page's examples as data (constants, a build function, what to draw).

Importing this package, or any scene module, never imports vpython: the browser view is loaded only
when a scene is shown (see scenes/view.py).
"""
