"""Started by every Python process of ``make test-perturbed`` (this folder is on PYTHONPATH):
installs the last-bit perturbation of ground motions (rockarch_perturb.py) there too."""

import os

if os.environ.get("ROCKARCH_PERTURB", "0") not in ("", "0"):
    import rockarch_perturb

    rockarch_perturb.install()
