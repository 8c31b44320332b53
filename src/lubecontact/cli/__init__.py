"""The ``lubecontact`` command: cli/main.py (parser, dispatch, solve, sweep, show), cli/transient.py
and cli/roughness.py (its subcommands), cli/exit_codes.py."""
