#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The command line of chainbench_tools.bench_table (the results tables: docs/results.md and the README headline); `--help` says more."""
from chainbench_tools.bench_table import main

if __name__ == "__main__":
    main()
