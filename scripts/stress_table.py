#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The command line of chainbench_tools.stress_table (the stress tables of docs/stress.md); `--help` says more."""
from chainbench_tools.stress_table import main

if __name__ == "__main__":
    main()
