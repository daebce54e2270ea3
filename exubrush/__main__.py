"""``python -m exubrush`` runs the command line."""

from exubrush.cli import main

main()
