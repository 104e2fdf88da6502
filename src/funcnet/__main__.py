"""``python -m funcnet``: the ``funcnet`` command."""

from funcnet.cli import main

main()
