# SPDX-License-Identifier: MIT
"""The Python side of chainbench: the results tables (bench_table), the stress tables
(stress_table), the report (report, report_conclusion), the plots (plotting) and the records
they pass each other (records). The scripts beside this package (scripts/bench_table.py, ...) are
its command lines."""
