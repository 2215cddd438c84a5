"""The ``rockarch`` command line (typer): one module per command group.

Theory: none of its own (each command names the equations of the library call it makes).

Every command accepts ``--json`` (one JSON object on stdout, SI units). Bad input prints one
line ``error: ...`` on stderr and exits with status 2. The commands parse options and call
the library (:func:`rockarch.systems.system`, :func:`rockarch.spectra.oas.compute_oas`, ...);
they compose nothing themselves.
"""

from rockarch.cli import (  # noqa: F401 - importing a module registers its commands
    archcmd,
    cache,
    fragility,
    oas,
    records,
    reproduce,
    risk,
    simulate,
    site,
)
from rockarch.cli._app import app
from rockarch.cli._common import fail

__all__ = ["app", "fail"]
