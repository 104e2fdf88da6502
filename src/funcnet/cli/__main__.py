"""``python -m funcnet.cli``: the ``funcnet`` command."""

from funcnet.cli import main

main()
