"""``python -m clearsim``: the command line of :mod:`clearsim.cli`."""

from .cli import main

if __name__ == "__main__":
    raise SystemExit(main())
