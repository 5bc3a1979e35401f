"""The ``thirdbody`` command installed with the package: the same program as the
Rust binary (``thirdbody_cli::app``), run in this process."""

import signal
import sys

from . import _thirdbody


def main() -> None:
    # Ctrl-C and a closed pipe end the program as they end the native binary.
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    sys.exit(_thirdbody._command_line(sys.argv))
