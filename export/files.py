"""Writing a program to a file whole: a temporary file in the same folder, renamed over the target."""
from __future__ import annotations

import os
import tempfile

from .lines import ProgramError


def check_path(path: str) -> None:
    """Raise ProgramError (one line) if a program obviously cannot be written to path."""
    if not path:
        raise ProgramError("cannot write the program to '': give a file name, like spring.py")
    if os.path.isdir(path):
        raise ProgramError(f"cannot write the program {path!r}: it is a directory")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise ProgramError(f"cannot write the program {path!r}: folder {folder!r} does not exist")
    if os.path.exists(path) and not os.access(path, os.W_OK):
        raise ProgramError(f"cannot write the program {path!r}: Permission denied")


def write_program(path: str, text: str) -> None:
    """Write text to path atomically: a temporary file in the same folder, then renamed over it.

    Raises ProgramError (one line) if the file cannot be written; no file is left behind then.
    """
    check_path(path)
    folder = os.path.dirname(os.path.abspath(path))
    temporary = None
    try:
        handle, temporary = tempfile.mkstemp(dir=folder, prefix=".program-", suffix=".tmp")
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            out.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)   # as an ordinary new file, not mkstemp's 0600
        os.replace(temporary, path)
    except OSError as problem:
        if temporary is not None and os.path.exists(temporary):
            os.remove(temporary)
        raise ProgramError(f"cannot write the program {path!r}: {problem.strerror or problem}") from None
