#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The command line of chainbench_tools.report: results/report.md from what scripts/run.sh left in
results/ (scripts/report.py RESULTS_DIR; --help says more)."""
from chainbench_tools.report import main

if __name__ == "__main__":
    main()
