"""Exit codes of the ``lubecontact`` command: 0 converged; 2 bad input (nothing is solved or
written); 3 no converged result (the file is still written, with converged = 0, or it could
not be written); 130 interrupted; 1 internal error (a bug)."""

EXIT_OK, EXIT_BAD_INPUT, EXIT_NOT_CONVERGED, EXIT_INTERRUPTED, EXIT_INTERNAL = 0, 2, 3, 130, 1
