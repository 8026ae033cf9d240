"""Both optimisations of the default study as its optimise jobs run them (set-up included, files
not written), for an A/B of two source trees (issue 27 item 6): time the two commands as whole
processes, in turn, and compare medians of several runs of each::

    git archive c61da5b | tar -x -C /tmp/base
    python benchmarks/study_ga_runs.py . FE.nc
    python benchmarks/study_ga_runs.py /tmp/base FE.nc

ROOT is the tree whose ``src/gearmesh`` and ``config/config.yaml`` are run; FE.nc the pair's
``fe_compliance.nc`` of a workflow run (the tables the jobs get from the fe stage, so neither side
times the FE tooth). Prints each run's wall time and its optimum's objective J on one line.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path


def main(root: str, fe_tables: str) -> None:
    root_path = Path(root).resolve()
    sys.path.insert(0, str(root_path / "src"))
    import xarray as xr
    import yaml

    from gearmesh.datasets.optimise import optimise_dataset
    from gearmesh.pairfile import load_pair

    config = yaml.safe_load((root_path / "config/config.yaml").read_text())
    pair = load_pair(root_path / "config/pairs/helical_z29_71_m5.yaml")
    fe = xr.load_dataset(fe_tables)
    out = []
    for name, section in config["optimise"].items():
        t0 = time.perf_counter()
        ds = optimise_dataset(pair, fe, **section, impact=config.get("impact"), tolerances=config.get("tolerances"))
        out.append(f"{name} {time.perf_counter() - t0:.2f} s J {float(ds['optimum_objective']):.6g}")
    print("; ".join(out))


if __name__ == "__main__":
    main(*sys.argv[1:3])
