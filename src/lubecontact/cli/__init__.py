"""The ``lubecontact`` command (cli/main.py) and its ``transient`` subcommand."""
